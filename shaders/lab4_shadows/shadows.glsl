// shadows.glsl — lab 4: how much of a light reaches world point P, read from the light's shadow
// map (lab4_shadows/shadow_maps.cpp renders them before the camera's pass). Included by
// lighting.glsl. 1 = lit, 0 = behind an opaque caster, in between: partly covered (PCF) or
// behind translucent casters, each letting 1 − opacity through.

// --- per shadow slot (up to 4 shadow-casting lights), specialization constants (lights.h) ---
// A pipeline contains only the lookups its scene needs, each PCF loop with a fixed trip count;
// a scene without shadow-casting lights has none at all (SHADOWS is false). Slot i's constants:
// SHADOW_KIND_i 0 no map, 1 2D (directional, spot), 2 cube (point); SHADOW_PCF_i N: an N×N kernel
// of taps; SHADOW_FILTER_i 0 nearest, 1 bilinear (both through the comparison sampler);
// SHADOW_TRANSLUCENT_i: the layers K of the transmittance map beside the depth map (0: none; a
// constant, so the lookup's loop over them is unrolled); SHADOW_LIGHT_i: whose map it is,
// LIGHT_ID of the light (−1: nobody's).
#define SHADOW_CONSTANTS(i, id)                                   \
    layout(constant_id = id) const int SHADOW_KIND_##i = 0;       \
    layout(constant_id = id + 1) const int SHADOW_PCF_##i = 1;    \
    layout(constant_id = id + 2) const int SHADOW_FILTER_##i = 0; \
    layout(constant_id = id + 3) const int SHADOW_TRANSLUCENT_##i = 0;      \
    layout(constant_id = id + 4) const int SHADOW_LIGHT_##i = -1;
SHADOW_CONSTANTS(0, 14) SHADOW_CONSTANTS(1, 19) SHADOW_CONSTANTS(2, 24) SHADOW_CONSTANTS(3, 29)
const bool SHADOWS = SHADOW_KIND_0 != 0 || SHADOW_KIND_1 != 0 || SHADOW_KIND_2 != 0 || SHADOW_KIND_3 != 0;

// The k-th light of a type (0 directional, 1 point, 2 spot), as SHADOW_LIGHT_i names it (lights.h:
// shadow_light_id), and its slot (−1: it casts no shadow). The light loops have constant trip
// counts, so once they are unrolled k is a constant and so is the slot: each light's code holds
// its own lookup and nothing else. Read from the light buffer instead, the slot would be a
// run-time switch, and a CPU rasterizer (lavapipe) runs every case of a switch for a block of
// pixels, keeping the one that applies: every light would pay for every map (README, "Two passes").
#define LIGHT_ID(type, k) ((type) * 64 + (k))
int shadow_slot_of(int light) {
    if (!SHADOWS) return -1;
    return light == SHADOW_LIGHT_0 ? 0 : light == SHADOW_LIGHT_1 ? 1 : light == SHADOW_LIGHT_2 ? 2 : light == SHADOW_LIGHT_3 ? 3 : -1;
}

struct ShadowSlot {
    mat4 view_projection;  // (world − origin) → the map's clip space (2D maps)
    vec4 origin;           // xyz: the light (spot, cube maps), the fitted box's centre (directional);
                           // positions are taken relative to it, where a float keeps their digits
    vec4 params;           // x: normal offset in world units (perspective maps: per unit of distance),
                           // y, z: the two constants of a perspective map's depth as a function of
                           // the distance along its axis (which function? the README, "Two passes";
                           // LightFrustum::depth_a() and depth_b() compute them); z > 0 also marks a
                           // perspective 2D map (spot); w: the texels per side the map pass drew,
                           // a square at the image's corner (lab 4 README, "Maps sized to the
                           // picture": the picture needs no more)
    vec4 translucent;      // x: how far (in depth) a receiver must lie behind a translucent caster to
                           // be behind it; perspective maps: divided by P's distance along the axis
};
layout(std140, set = 0, binding = 3) uniform Shadows { ShadowSlot shadow_slots[4]; };
// The same depth maps twice: read as numbers (their size) and through a comparison sampler
// (each gather compares four texels with the reference depth).
layout(set = 0, binding = 4) uniform sampler2D shadow_depth[4];
layout(set = 0, binding = 5) uniform sampler2DShadow shadow_compare[4];
// Point lights' cube maps, read as 2D arrays of their six faces (layer = face, see shadow_cube).
layout(set = 0, binding = 6) uniform sampler2DArray cube_depth[4];
layout(set = 0, binding = 7) uniform sampler2DArrayShadow cube_compare[4];
// Translucent casters (the second lesson): their transmittance maps and translucent_light().
#include "translucent_shadows.glsl"

// PCF's share of one gather: the four texels it compared, c = (0,1) (1,1) (1,0) (0,0) as
// textureGather returns them, for the gather at columns bx, bx + 1 and rows by, by + 1 of an N×N
// footprint (N = pcf), weighted per axis: nearest 1 (the padding texel N: 0, f = 0); bilinear
// 1 − f, 1, …, 1, f. Both lookups below add these up over the footprint's gathers.
float pcf_share(vec4 c, int bx, int by, int pcf, vec2 f) {
    const vec2 w0 = vec2(bx == 0 ? 1.0 - f.x : 1.0, by == 0 ? 1.0 - f.y : 1.0);
    const vec2 w1 = vec2(bx + 1 == pcf ? f.x : 1.0, by + 1 == pcf ? f.y : 1.0);
    return c.w * w0.x * w0.y + c.z * w1.x * w0.y + c.x * w0.x * w1.y + c.y * w1.x * w1.y;
}

// Directional and spot lights: P projected into the map; PCF averages N×N taps one texel apart.
float shadow_2d(sampler2D depth_map, sampler2DShadow compare_map, sampler2DArray translucent_map, int pcf, int filter_mode,
                int layers, ShadowSlot s, vec3 P, vec3 N) {
    // Normal offset: look the map up a little off the surface (in texels), so a surface does not
    // shadow itself where the map's texel stands at an angle to it (acne).
    const bool perspective = s.params.z > 0.0;
    const float distance = perspective ? length(P - s.origin.xyz) : 1.0;
    const vec3 at = P - s.origin.xyz + N * s.params.x * distance;  // relative to the origin
    const vec4 clip = s.view_projection * vec4(at, 1.0);
    const bool behind = !(clip.w > 0.0);  // behind a spot light: outside its cone anyway
    const float inv_w = 1.0 / clip.w;  // w: P's distance along a spot's axis; 1 for a directional map
    const vec3 ndc = clip.xyz * inv_w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    // Outside the map's coverage nothing was fitted to cast onto it: lit. No early return and no
    // fetch under a per-pixel condition: Mesa 22.3's lavapipe crashes (SIGSEGV) on such fetches in
    // this function (random scenes; a spot's map in slot 1 after a cube in slot 0). Every pixel
    // fetches, at the map's centre when it is outside, and the answer is picked at the end.
    const bool outside = behind || !(all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))));
    const vec2 lookup = outside ? vec2(0.5) : uv;
    // P's depth as the light sees it. The map ends just beyond the farthest caster: a receiver
    // farther away compares as 1, lit where the texel holds no caster (cleared to 1), in shadow
    // where it does. In front of the near plane (0): only casters clamped there can be nearer.
    const float ref = clamp(ndc.z, 0.0, 1.0);
    const float tolerance = s.translucent.x * inv_w;  // translucent casters, see above
    // Translucent casters: the light their layers let through to P (once, not per tap).
    // The map's drawn square: `used` texels per side of the image's `size`.
    const float used = s.params.w;
    const vec2 size = vec2(textureSize(depth_map, 0));
    const float through = translucent_light(layers, translucent_map, vec3(lookup * used / size, 0.0), ref, tolerance);
    // PCF: N×N taps one texel apart, each lit where the comparison sampler says so (the stored
    // depth carries the bias: the pass put it there). Nearest: each tap compares its own texel.
    // Bilinear: each tap compares the four texels around it and weights the results like a linear
    // filter (what a comparison sampler does with LINEAR; done by hand, as that needs a depth
    // format the device filters: lavapipe has none). Both read the comparison sampler four texels
    // at a time (textureGather): N taps touch N (nearest) or N + 1 (bilinear) texels per axis, so
    // 3×3 PCF costs 4 gathers, not 9 lookups, and a single tap 1 gather (pcf_share weights each;
    // a plain shadow lookup, texture(compare_map, …), crashes Mesa 22.3's lavapipe here).
    const vec2 texel = filter_mode == 1 ? lookup * used - 0.5 : lookup * used;
    const vec2 base = floor(texel) - float(pcf / 2);  // the first texel of the footprint
    const vec2 f = filter_mode == 1 ? fract(texel) : vec2(0.0);
    float sum = 0.0;
    for (int by = 0; by <= pcf; by += 2) {
        for (int bx = 0; bx <= pcf; bx += 2) {
            // Columns bx, bx + 1 and rows by, by + 1 of the footprint, compared with ref at once.
            sum += pcf_share(textureGather(compare_map, (base + vec2(bx, by) + 1.0) / size, ref), bx, by, pcf, f);
        }
    }
    const float opaque = sum / float(pcf * pcf);
    return outside ? 1.0 : opaque * through;
}

// For P at v from the light (v = P − light): the cube face it falls in and where on that face
// (cube_face_uv: s, t in [0, 1] and the layer, 0…5 for +X, −X, +Y, −Y, +Z, −Z), its distance along
// that face's axis, and the depth that face's projection stored for that distance (exercise
// cube_face_depth).
// EXERCISE cube_face_depth: cube_face_uv: which face does direction d fall in, and at which (s, t) on it does a cube sampler read d — the face and texel the map pass drew there (fit_point()'s face views, whose up vectors follow the spec)? Break ties x before y before z. face_distance: how far is P along that face's axis (each face is a 90° perspective view along ±X, ±Y or ±Z)? cube_depth_of: what depth did that face's projection store for that distance (the comment on params in ShadowSlot)? Read the Vulkan spec's "Cube Map Face Selection" and "Cube Map Face Coordinates". Wrong: point lights cast no shadow, or shadows that bend, leak away from the six axes, or fall mirrored or on the wrong side. Checked by Lab4Shadows.PointLightMatchesTheReference, Lab4Shadows.PointLightCubeSeamsShowNoCracks.
// STUB: float face_distance(vec3 v) { return length(v); }  // the distance to the light, not along a face's axis
// STUB: float cube_depth_of(vec3 v, ShadowSlot s) { return 0.0; }  // everything in front of every caster: no shadow
// STUB: vec3 cube_face_uv(vec3 d) { return vec3(0.5, 0.5, 0.0); }  // every direction reads the middle of face +X
float face_distance(vec3 v) {
    const vec3 a = abs(v);
    return max(a.x, max(a.y, a.z));
}

float cube_depth_of(vec3 v, ShadowSlot s) {
    return s.params.y - s.params.z / max(face_distance(v), 1e-30);
}

// Vulkan's cube sampling (spec, "Cube Map Face Selection"): the largest coordinate picks the face,
// the other two divided by it give (s, t) in [0, 1]. Ties go to x, then y.
vec3 cube_face_uv(vec3 d) {
    const vec3 a = abs(d);
    const bool x = a.x >= a.y && a.x >= a.z, y = !x && a.y >= a.z;
    const float major = x ? a.x : (y ? a.y : a.z);
    const vec2 sc_tc = x ? vec2(d.x > 0.0 ? -d.z : d.z, -d.y)                   // ±X: (∓z, −y)
                     : (y ? vec2(d.x, d.y > 0.0 ? d.z : -d.z)                   // ±Y: (x, ±z)
                          : vec2(d.z > 0.0 ? d.x : -d.x, -d.y));                // ±Z: (±x, −y)
    const float layer = x ? (d.x > 0.0 ? 0.0 : 1.0) : (y ? (d.y > 0.0 ? 2.0 : 3.0) : (d.z > 0.0 ? 4.0 : 5.0));
    return vec3(sc_tc / major * 0.5 + 0.5, layer);
}
// END EXERCISE

// Point lights: the direction from the light to P picks the face and texel, and PCF runs on that
// face's texel grid as shadow_2d does (four compared texels per gather). The maps are read as a 2D
// array of the six faces, the face picked here once, not by a cube sampler: a CPU rasterizer
// (lavapipe) picks the face anew for every lookup (a 3×3 kernel cost 2.5× as much). The kernel
// stays on P's face: a gather past its edge is moved back inside, so the edge texels count twice
// there — less than a texel of blur, and no crack, as every texel is compared with P's depth in
// its own face. (Following the kernel into the neighbouring face costs 1.8× as much here.)
float shadow_cube(sampler2DArray depth_map, sampler2DArrayShadow compare_map, sampler2DArray translucent_map, int pcf,
                  int filter_mode, int layers, ShadowSlot s, vec3 P, vec3 N) {
    vec3 v = P - s.origin.xyz;
    v += N * s.params.x * face_distance(v);  // normal offset, texels grow with distance
    const float z = face_distance(v);
    // P at the light itself: lit. As in shadow_2d, no early return (lavapipe): every pixel reads,
    // along +X when it has no direction, and the answer is picked at the end.
    const bool at_light = !(z > 0.0);
    const vec3 to_p = at_light ? vec3(1.0, 0.0, 0.0) : v;
    const vec3 face = cube_face_uv(to_p);  // (s, t, layer)
    // Beyond the far plane (past the farthest caster): compared as 1, as in shadow_2d.
    const float ref = clamp(cube_depth_of(to_p, s), 0.0, 1.0);
    const float tolerance = layers > 0 ? s.translucent.x / z : 0.0;  // translucent casters, see above
    // The footprint and its weights, as in shadow_2d, on the face's drawn square (used² of size²).
    const float used = s.params.w;
    const float size = float(textureSize(depth_map, 0).x);
    const float through = translucent_light(layers, translucent_map, vec3(face.xy * used / size, face.z), ref, tolerance);
    const vec2 texel = filter_mode == 1 ? face.xy * used - 0.5 : face.xy * used;
    const vec2 base = floor(texel) - float(pcf / 2);
    const vec2 f = filter_mode == 1 ? fract(texel) : vec2(0.0);
    const vec2 inside = vec2(1.0 / size, (used - 1.0) / size);  // a gather's centre, a texel inside the square
    float sum = 0.0;
    for (int by = 0; by <= pcf; by += 2) {
        for (int bx = 0; bx <= pcf; bx += 2) {
            const vec2 st = clamp((base + vec2(bx, by) + 1.0) / size, inside.x, inside.y);
            sum += pcf_share(textureGather(compare_map, vec3(st, face.z), ref), bx, by, pcf, f);
        }
    }
    const float opaque = sum / float(pcf * pcf);
    return at_light ? 1.0 : opaque * through;
}

// Slot i's lookup with slot i's constants (samplers are picked with constant indices).
#define SHADOW_SLOT(i) case i: \
    if (SHADOW_KIND_##i == 1) return shadow_2d(shadow_depth[i], shadow_compare[i], translucency[i], SHADOW_PCF_##i, SHADOW_FILTER_##i, SHADOW_TRANSLUCENT_##i, shadow_slots[i], P, N); \
    if (SHADOW_KIND_##i == 2) return shadow_cube(cube_depth[i], cube_compare[i], cube_translucency[i], SHADOW_PCF_##i, SHADOW_FILTER_##i, SHADOW_TRANSLUCENT_##i, shadow_slots[i], P, N); \
    break;
float shadow_factor(int slot, vec3 P, vec3 N) {
    switch (slot) { SHADOW_SLOT(0) SHADOW_SLOT(1) SHADOW_SLOT(2) SHADOW_SLOT(3) }
    return 1.0;  // casts no shadow
}
