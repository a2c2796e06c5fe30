#version 450
// Lab 4: with shadows (shadows.glsl) and the material's opacity as alpha.
// Lab 3: the lighting equation per pixel (flat and Phong shading) with the material's texture
// maps, or the interpolated vertex color (Gouraud: untextured). See docs/lighting.md.
#extension GL_GOOGLE_include_directive : require
// Lab 4: built twice more for translucent objects: with TRANSLUCENT_LAYER (lit_layer.frag.spv) and
// with TEXTURED_LAYER (textured_layer.frag.spv: both), each fragment stored in its pixel's list of
// layers instead of written (translucent_layers.glsl; the resolve composes them in depth order).
#ifdef TEXTURED_LAYER
#define TEXTURED
#define TRANSLUCENT_LAYER
#endif
#include "lighting.glsl"

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec3 in_world_tangent;
layout(location = 3) in vec3 in_gouraud_color;
layout(location = 4) in float in_bad;
layout(location = 5) in vec2 in_uv;

#ifdef TRANSLUCENT_LAYER
#include "translucent_layers.glsl"
// The depth test before the shader, not after it: a fragment behind the opaque surface must not
// run at all, or it would store a layer no one sees (a shader that writes memory is otherwise
// tested late, after its writes).
layout(early_fragment_tests) in;
#else
layout(location = 0) out vec4 out_color;
#endif

// Lab 3: the material's maps (set 1), in the module built with TEXTURED (textured.frag.spv) for
// materials that have maps; lit.frag.spv declares no samplers. The sampler decodes sRGB to
// linear and filters (mipmaps, anisotropy) as the material's sampler says, or lookup()'s probes do.
#ifdef TEXTURED
layout(set = 1, binding = 0) uniform sampler2D albedo_map;
layout(set = 1, binding = 1) uniform sampler2D specular_map;
layout(set = 1, binding = 2) uniform sampler2D emissive_map;

// One lookup of a map: the sampler's own filter, or with "anisotropic": "probes" the shader's
// anisotropic filter. A pixel's footprint in the map is the parallelogram spanned by the UV
// derivatives (in texels: j_x = size·∂uv/∂x, j_y = size·∂uv/∂y); at a grazing angle it is long
// and thin. One trilinear lookup blurs over its major axis; n probes spaced along that axis each
// cover major/n of it, so each reads a sharper level (the EXT_texture_filter_anisotropic rule;
// a probe is trilinear, or with "mipmaps": "nearest" bilinear on the nearest level: cheaper):
//   n = min(⌈major / max(minor, 1)⌉, PROBES),   LOD = log2(max(major / n, minor)).
// (Magnified, major ≤ 1 texel: n = 1, no blur.) PROBES is a specialization constant: 0 compiles
// the plain lookup and nothing else. The derivatives are taken before the loop (uniform control flow).
vec4 lookup(sampler2D map, vec2 uv) {
    if (PROBES == 0) return texture(map, uv);
    const vec2 size = vec2(textureSize(map, 0));
    const vec2 dx = dFdx(uv), dy = dFdy(uv);
    const float lx = length(dx * size), ly = length(dy * size);
    const float major = max(lx, ly), minor = min(lx, ly);
    const vec2 axis = lx >= ly ? dx : dy;  // the major axis, in UV
    const int n = int(clamp(ceil(major / max(minor, 1.0)), 1.0, float(PROBES)));
    const float lod = log2(max(max(major / float(n), minor), 1e-6));
    vec4 sum = vec4(0.0);
    for (int i = 0; i < n; ++i) sum += textureLod(map, uv + axis * ((float(i) + 0.5) / float(n) - 0.5), lod);
    return sum / float(n);
}

// The seed's distorted-UV multi-sampling: a small wobble of the UVs that also depends on the
// world position P, blended with the map at two other scales. Repeats of a tiled map no longer
// line up, so the tiling is much harder to see.
vec3 albedo_texel(Material m, vec2 uv, vec3 P) {
    if (!DISTORTED) return lookup(albedo_map, uv).rgb;
    // EXERCISE distorted_uv: the seed's distorted albedo: which lookups (lookup(): the sampler or the probes) at uv and P, wobbled or scaled, blended how (GpuMaterial::distortion)? Read this lab's README "The equation". Wrong: plain tiling, or a jump as uv_offset moves a whole repeat. Checked by Lab3PlainSampler.DistortedAlbedo, Lab3Render.DistortedSampling, Lab3Render.DistortedSamplingOwnNumbers, Lab3Render.DistortedSamplingWholeOffsetRepeat, Lab3Render.DistortedSamplingWholeOffsetMirror, Lab3Render.DistortedSamplingHugeOffset.
    // STUB: return lookup(albedo_map, uv).rgb;  // no distortion: the tiling shows as plainly as without it
    const vec4 k0 = m.distortion[0], k1 = m.distortion[1], k2 = m.distortion[2], k3 = m.distortion[3], k4 = m.distortion[4];
    const vec2 d = uv + vec2(k0.x * sin(k0.z * uv.y + k1.x * P.y + k3.x), k0.y * cos(k0.w * uv.x + k1.y * P.x + k3.y));
    const vec3 t0 = lookup(albedo_map, d).rgb, t1 = lookup(albedo_map, k1.z * uv + k4.xy).rgb;
    return mix(mix(t0, t1, k2.x), lookup(albedo_map, k1.w * uv + k4.zw).rgb, k2.y);
    // END EXERCISE
}

// The material with its maps read at the material's tiled and shifted UVs (exercise texture_terms;
// docs/lighting.md, "Lab 3: textured terms"); a map the material lacks is not sampled at all.
// uv: the mesh's UV in, the UV the maps were read at out (the mip-level view reads it).
Material textured(Material m, inout vec2 uv, vec3 P) {
    // EXERCISE texture_terms: the material with its maps, read at the material's UV: how do uv_scale (tiles) and uv_offset (shifts, in repeats) turn the mesh's uv into it, in which order, and where are they in m.uv_transform? Does A (albedo_texel), S, E scale or add to albedo, specular, emissive; where is emissive_strength; which maps exist (ALBEDO_MAP…), each read by lookup()? Read docs/lighting.md "Lab 3: textured terms", docs/scene-format.md (uv_scale, uv_offset), the Vulkan spec's "Wrapping Operation". Wrong: plain colours, the map once per object whatever uv_scale says or shifted by the wrong amount, a washed-out map, a grid that does not glow. Checked by Lab3PlainSampler.MapTermsAtTheMeshUv, Lab3PlainSampler.UvScaleAndOffset, Lab3Render.AlbedoMapMagnified, Lab3Render.NearestFilterWithUvScaleAndOffset, Lab3Render.SpecularMap, Lab3Render.EmissiveMap, Lab3Render.AllThreeMapsLit.
    // STUB: // the mesh's UVs as they are and no map read: every textured material shows its plain colours
    uv = uv * m.uv_transform.xy + m.uv_transform.zw;
    if (ALBEDO_MAP) m.albedo.rgb *= albedo_texel(m, uv, P);
    if (SPECULAR_MAP) m.specular.rgb *= lookup(specular_map, uv).rgb;
    if (EMISSIVE_MAP) m.emissive.rgb += m.distortion[2].z * lookup(emissive_map, uv).rgb;
    // END EXERCISE
    return m;
}

// Mip-level view: the level the first map's lookup reads (fractional between two levels),
// as a colour: 0 white, 1 red, 2 yellow, 3 green, 4 cyan, 5 blue, 6 and up magenta.
vec3 mip_tint(vec2 uv) {
    const vec3 colors[7] = vec3[](vec3(1, 1, 1), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0), vec3(0, 1, 1),
                                  vec3(0, 0, 1), vec3(1, 0, 1));
    const vec2 lod = ALBEDO_MAP ? textureQueryLod(albedo_map, uv) : SPECULAR_MAP ? textureQueryLod(specular_map, uv)
                                                                                  : textureQueryLod(emissive_map, uv);
    const float level = clamp(lod.x, 0.0, 6.0);
    return mix(colors[int(floor(level))], colors[min(int(floor(level)) + 1, 6)], fract(level));
}
#else
Material textured(Material m, inout vec2 uv, vec3 P) { return m; }
vec3 mip_tint(vec2 uv) { return vec3(1.0); }
#endif

void main() {
    vec3 color;
    const float alpha = materials[object.material].albedo.a;  // lab 4: opacity (blended if < 1)
    if (SHADING == SHADING_GOURAUD) {
        color = in_gouraud_color;
        lab_bad = in_bad > 0.0;
    } else {
        const vec3 P = in_world_position;
        const vec3 to_eye = frame.camera_position.xyz - P;
        // EXERCISE face_normal: N for the flat and Phong models (docs/lighting.md "Shading models"). Flat: the triangle's own normal, which no vertex carries and no input gives: what does a fragment shader know about how P changes across the triangle, and which way must the normal point (towards the eye, on the side of the triangle the camera sees, whatever the winding and Vulkan's downward y do to a cross product)? Phong: the interpolated normal, no longer unit, possibly zero. Degenerate cases: safe_normalize(). Read the GLSL spec's "Derivative Functions", docs/lighting.md "Numerical safety". Wrong: no facets under flat shading, black or inverted facets, black spots where the normals cancel. Checked by Lab2Term.FlatFacets, Lab2Shading.FlatVsPhong.
        // STUB: const vec3 N = safe_normalize(in_world_normal, safe_normalize(to_eye, vec3(0.0, 0.0, 1.0)));  // no facets: every model Phong's
        // The triangle's own (geometric) normal from the screen-space derivatives of the
        // position, turned towards the eye: every drawn triangle is a front face.
        vec3 face = safe_normalize(cross(dFdx(P), dFdy(P)), safe_normalize(to_eye, vec3(0.0, 0.0, 1.0)));
        if (dot(face, to_eye) < 0.0) face = -face;
        // Flat: the face normal. Phong: the interpolated normal, renormalized (a zero
        // interpolated normal falls back to the face normal).
        // Lab 4: a translucent object's back faces are drawn too; their normal turns to the viewer.
        const vec3 N = SHADING == SHADING_FLAT ? face : (gl_FrontFacing ? 1.0 : -1.0) * safe_normalize(in_world_normal, face);
        // END EXERCISE
        const vec3 V = safe_normalize(to_eye, N);  // the eye on the surface: V = N
        vec2 uv = in_uv;  // textured() turns it into the UV the maps are read at
        color = shade(textured(materials[object.material], uv, P), P, N, V, in_world_tangent);
        if (MIP_VIEW && (ALBEDO_MAP || SPECULAR_MAP || EMISSIVE_MAP)) {
            // The level depends on how fast the UV changes across the pixel, which uv_offset (a
            // constant shift) does not change: the UV textured() makes with the offset left out,
            // so that a large offset's rounding does not show in the tint.
            Material unshifted = materials[object.material];
            unshifted.uv_transform.zw = vec2(0.0);
            vec2 tiled = in_uv;
            textured(unshifted, tiled, P);
            color = mix(color, mip_tint(tiled), 0.7);
        }
    }
    // The self-test proves the check works: a quiet NaN (exponent all ones, top mantissa bit)
    // made from the bits of a uniform (ambient.a = 0), so no compiler can know it is a NaN and
    // fold it away (as it may fold x / x to 1), added to the color like a real bad intermediate.
    if (NAN_CHECK == 2) color += vec3(uintBitsToFloat(0x7fc00000u | floatBitsToUint(frame.ambient.a)));
    if (NAN_CHECK != 0) {
        check(color);
        if (lab_bad) color = vec3(1.0, 0.0, 1.0);
    }
#ifdef TRANSLUCENT_LAYER
    color = clamp(color, vec3(0.0), vec3(65504.0));  // the largest half: an overflowing colour stays bright
    const uint color_ba = packHalf2x16(vec2(color.b, alpha));
    // Every fragment, stored or not, counts in its pixel's fragment count and optical depth (the α
    // the resolve would compose: the stored half): a pixel that loses one can tell, and still gets
    // its layers' whole transmittance (translucent_resolve.frag).
    const uint pixel = layer_pixel();
    atomicAdd(heads[layer_stats.pixels + pixel], 1u);
    atomicAdd(heads[2u * layer_stats.pixels + pixel], optical_depth(unpackHalf2x16(color_ba).y));
    // Take the pool's next node; past its end the fragment is counted and lost.
    const uint node = atomicAdd(taken, 1u);
    if (node >= uint(nodes.length())) {
        atomicAdd(layer_stats.dropped, 1u);
        return;
    }
    nodes[node].color_rg = packHalf2x16(color.rg);
    nodes[node].color_ba = color_ba;
    nodes[node].depth = gl_FragCoord.z;
    // Push it onto the pixel's list: the old head becomes its next. One atomic exchange, so two
    // fragments of the same pixel (two objects, two faces) never lose each other.
    nodes[node].next = atomicExchange(heads[pixel], node);
#else
    out_color = vec4(color, alpha);
#endif
}
