// translucent_shadows.glsl — lab 4's second lesson: shadows of translucent casters. A light's
// transmittance map (lab4_shadows/translucent_shadows.cpp renders it beside the depth map) holds,
// per texel, the translucent casters' front faces along its ray, nearest first, one per layer: where
// each is and how much light it lets through. Included by shadows.glsl; its lookups call
// translucent_light() once per lookup.

// Translucent casters, K layers per face (a 2D map has one face, 0; a cube its six, 0…5 as in its
// depth map), all of a map's layers in one array, in the order the map pass allocates them
// (TranslucentShadows::make_map(), lab4_shadows/translucent_shadows.cpp). A face's layer k holds
// the (k+1)-th front face (as the light sees them) along the texel's ray, r = its 1 − opacity,
// g = its depth; r = g = 1 where there is none. (Past K faces the last layer holds
// r = Π(1 − opacity) of the rest, g = the nearest of them.)
layout(set = 0, binding = 8) uniform sampler2DArray translucency[4];
layout(set = 0, binding = 9) uniform sampler2DArray cube_translucency[4];  // a cube's faces, K layers each

// A receiver less than 2 texels (in world units) behind the nearest translucent caster is that
// caster itself. The lookups turn that into a tolerance in depth: the map's number (ShadowSlot's
// `translucent`, TranslucentShadows::tolerance()) divided by z = P's distance along the map's axis
// (an orthographic map: z = 1). A fixed tolerance in depth would not do: a texel widens with
// distance, and perspective depth crowds towards 1 (1e-4 of it is metres at a far light).

// The light the translucent casters let through to P at depth `ref`: `at` = (s, t, face) in the
// map, `tolerance` in depth (see above). `layers` (K) is a specialization constant: without
// translucent casters (0) there is no lookup at all, and the loop over the layers unrolls. (A bound
// read from a uniform made lavapipe, Mesa 22.3, grow by megabytes every frame.)
float translucent_light(int layers, sampler2DArray map, vec3 at, float ref, float tolerance) {
    // EXERCISE translucent_tap: read P's texel in each of the face's K layers (which array layer is layer k of face at.z?) and decide, layer by layer, what the face it holds does to the light on its way to P: which faces dim it, by how much, and which must not — P's own face among them, at P's depth give or take the rounding that `tolerance` covers? What does a layer hold where no face is? Read the comment on `translucency` above and the lab 4 README, "Translucent objects". Wrong: a glass object casts no shadow, shadows itself, or the floor under two panes gets one pane's shadow. Checked by Lab4Shadows.TranslucentShadowFromAFarSpot, Lab4Shadows.TranslucentShadowInteriorWithin2Of255, Lab4Shadows.TwoOverlappingTranslucentObjectsMultiply, Lab4Translucency.TranslucentCubesLitFacesDoNotShadowThemselves, Lab4Translucency.TranslucentReceiverUnderATranslucentCaster.
    // STUB: return 1.0;  // translucent casters let all the light through
    float lit = 1.0;
    for (int k = 0; k < layers; ++k) {
        // r = the layer's face's 1 − opacity, g = its depth (r = g = 1: no face).
        const vec2 layer = texture(map, vec3(at.xy, at.z * float(layers) + float(k))).rg;
        if (ref > layer.g + tolerance) lit *= layer.r;  // its face lies in front of P, P's own face not
    }
    return lit;
    // END EXERCISE
}
