// translucent_shadows.glsl — lab 4's second lesson: shadows of translucent casters. A light's
// transmittance map (lab4_shadows/translucent_shadows.cpp renders it beside the depth map) says,
// per texel, how much light the translucent casters along its ray let through and where the
// nearest of them is. Included by shadows.glsl; its lookups call tap() for every PCF tap.

// Translucent casters: r = Π(1 − opacity) of the front faces (as the light sees them) along
// the texel's ray, g = the depth of the nearest one.
layout(set = 0, binding = 8) uniform sampler2D translucency[4];
layout(set = 0, binding = 9) uniform sampler2DArray cube_translucency[4];  // a cube's faces (layer = face)

// A receiver less than 2 texels (in world units) behind the nearest translucent caster is that
// caster itself. In depth that is K / z, z = P's distance along the map's axis (an orthographic
// map: z = 1, K as it is; K from the map, translucent_shadows.cpp): a fixed tolerance in depth
// would not do, perspective depth crowds towards 1 (1e-4 of it is metres at a far light).

// One tap's light: `lit` (1 or 0) from the depth compare, and what the translucent casters along
// the ray do to it (exercise translucent_tap; `tolerance`, in depth, see above).
float tap(float lit, bool translucent, vec2 transmittance, float ref, float tolerance) {
    // EXERCISE translucent_tap: when does the light pass through the translucent casters before reaching P, and how much of it is left (what do r and g of the transmittance map hold)? Wrong: a glass object casts no shadow, or shadows itself. Checked by Lab4Shadows.TranslucentShadowFromAFarSpot, Lab4Shadows.TranslucentShadowInteriorWithin2Of255, Lab4Shadows.TwoOverlappingTranslucentObjectsMultiply.
    // STUB: return lit;  // translucent casters let all the light through
    if (translucent && ref > transmittance.g + tolerance) lit *= transmittance.r;
    return lit;
    // END EXERCISE
}
