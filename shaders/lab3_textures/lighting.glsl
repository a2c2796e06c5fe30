// lighting.glsl — the lighting equation of docs/lighting.md (since lab 2), included by lit.vert
// (Gouraud: evaluated per vertex) and lit.frag (flat and Phong shading: per pixel).
// Linear RGB throughout; the *_SRGB render target clamps to [0, 1] and encodes.

// --- which parts this pipeline variant contains (specialization constants, lights.h) ---
layout(constant_id = 0) const int LIGHTING_MODEL = 2;  // see the MODEL_* values below
layout(constant_id = 1) const int SHADING = 2;         // 0 flat, 1 Gouraud, 2 Phong
// How many lights of each type: known when the pipeline is built, so each loop below has a fixed
// trip count (0 = no loop at all). On lavapipe a loop whose count is read from a buffer cost
// twice the whole frame: every SIMD lane then fetches its own copy of every light.
layout(constant_id = 2) const int DIRECTIONAL_COUNT = 1;
layout(constant_id = 3) const int POINT_COUNT = 1;
layout(constant_id = 4) const int SPOT_COUNT = 1;
layout(constant_id = 5) const int DISTRIBUTION = 0;    // Cook-Torrance: 0 GGX, 1 Beckmann
layout(constant_id = 6) const int NAN_CHECK = 0;       // 0 off, 1 NaN/Inf → magenta, 2 also inject a NaN
layout(constant_id = 7) const int TOON_BANDS = 4;
// Lab 3: which maps this material has and how it reads them (per material, see lit.frag).
layout(constant_id = 8) const bool ALBEDO_MAP = false;
layout(constant_id = 9) const bool SPECULAR_MAP = false;
layout(constant_id = 10) const bool EMISSIVE_MAP = false;
layout(constant_id = 11) const bool DISTORTED = false;
layout(constant_id = 12) const int PROBES = 0;  // anisotropic probes: the most per lookup, 0 = a plain lookup
layout(constant_id = 13) const bool MIP_VIEW = false;

const int MODEL_LAMBERT = 0, MODEL_PHONG = 1, MODEL_BLINN_PHONG = 2, MODEL_TOON = 3, MODEL_OREN_NAYAR = 4,
          MODEL_MINNAERT = 5, MODEL_COOK_TORRANCE = 6, MODEL_WARD = 7;
const int SHADING_FLAT = 0, SHADING_GOURAUD = 1, SHADING_PHONG = 2;

const float PI = 3.14159265358979;
// Numerical safety (docs/lighting.md, "Stress cases"); the CPU reference uses the same values.
const float MIN_LENGTH2 = 1e-20;      // a vector shorter than 1e-10 has no direction
const float MIN_DENOMINATOR = 1e-6;   // attenuation(): a light on a surface stays finite (exercise attenuation)
const float MIN_COS_VIEW = 1e-3;      // N·V in divisions (Minnaert, Cook-Torrance, Ward)
const float MIN_COS_HALF = 1e-4;      // N·H in divisions (Beckmann, Ward)
const float MIN_ALPHA = 1e-3;         // Cook-Torrance α = max(roughness², MIN_ALPHA)

// --- scene data (lights.h has the C++ side of every layout) ---
layout(set = 0, binding = 0) uniform FrameUniforms {
    mat4 view;
    mat4 projection;
    vec4 camera_position;  // xyz: the eye in world space
    vec4 ambient;          // rgb: ambient color × intensity; a: 0 (the NaN self-test builds on it)
} frame;

struct DirectionalLight { vec4 direction; vec4 radiance; };
struct PointLight { vec4 position; vec4 radiance; vec4 attenuation; };
struct SpotLight { vec4 position; vec4 direction; vec4 radiance; vec4 attenuation; vec4 cone; };

// A uniform buffer (4-6 KB, lights.h): read at the same address by every pixel, which a CPU
// rasterizer does once per group of pixels; a storage buffer it reads lane by lane.
layout(std140, set = 0, binding = 1) uniform Lights {
    uvec4 counts;  // x: directional, y: point, z: spot
    DirectionalLight directional[8];
    PointLight point[32];
    SpotLight spot[32];
} lights;

struct Material {
    vec4 albedo;    // rgb
    vec4 specular;  // rgb: specular color, a: shininess
    vec4 emissive;  // rgb
    vec4 f0;        // rgb: Cook-Torrance F0, a: roughness
    vec4 params;    // x, y: Ward roughness along tangent / bitangent, z: Minnaert k
    vec4 uv_transform;   // lab 3: xy uv_scale, zw uv_offset
    vec4 distortion[5];  // amplitude, frequency | position_frequency, scales | weights, emissive_strength |
                         // [3], [4]: what uv_offset's whole repeats change (lights.cpp, pack_materials)
};
// A uniform buffer, not a storage buffer: every pixel reads its material, and on a CPU
// rasterizer (lavapipe) uniform reads are much cheaper than storage-buffer reads.
const int MAX_MATERIALS = 128;
layout(std140, set = 0, binding = 2) uniform Materials { Material materials[MAX_MATERIALS]; };

layout(push_constant) uniform ObjectConstants {
    mat4 model;              // model → world
    vec4 normal_matrix[3];   // the normal matrix's columns (renderer.cpp), scaled to max |element| = 1
    uint material;           // index into materials[]
} object;

// --- NaN / Inf detection (NAN_CHECK != 0): any bad intermediate paints the pixel magenta ---
// A 32-bit float is NaN or ±Inf exactly when its 8 exponent bits are all ones. The test looks
// at the bits, not through isnan()/isinf(): a driver's compiler may assume that no NaN or Inf
// ever occurs and fold those two away (real GPUs do), but it must keep integer operations.
bool lab_bad = false;
bool not_finite(float x) {
    const uint EXPONENT_BITS = 0x7f800000u;
    return (floatBitsToUint(x) & EXPONENT_BITS) == EXPONENT_BITS;
}
void check(float x) {
    if (NAN_CHECK != 0 && not_finite(x)) lab_bad = true;
}
void check(vec3 v) {
    if (NAN_CHECK != 0 && (not_finite(v.x) || not_finite(v.y) || not_finite(v.z))) lab_bad = true;
}

// --- helpers ---
vec3 safe_normalize(vec3 v, vec3 fallback) {
    const float len2 = dot(v, v);
    return len2 > MIN_LENGTH2 ? v * inversesqrt(len2) : fallback;
}

// pow(x, n) for x ≥ 0 with pow(x, 0) = 1 (GLSL leaves pow(0, 0) undefined).
float power(float x, float n) {
    if (n <= 0.0) return 1.0;
    return x > 0.0 ? pow(x, n) : 0.0;
}

// Light falloff: the fraction of a light's radiance left at the distance d (exercise attenuation).
float attenuation(vec3 k, float d) {
    // EXERCISE attenuation: what fraction of a light's radiance is left after the distance d, given k = (constant, linear, quadratic)? And if all are zero, or their sum tiny? Read docs/lighting.md "Light types", "Numerical safety" (MIN_DENOMINATOR). Wrong: lights with no falloff look like flat floodlights, near and far walls equally lit; Inf/NaN pixels. Checked by Lab2Term.PointLightFalloff, Lab2Render.PointLights, Lab2Stress.PointLightAtAVertexStaysFinite.
    // STUB: return 1.0;  // no falloff: every point light reaches everywhere at full strength
    if (k.x + k.y + k.z <= 0.0) return 1.0;
    return 1.0 / max(k.x + k.y * d + k.z * d * d, MIN_DENOMINATOR);
    // END EXERCISE
}

// Spot cone: cos_theta = cos of the angle between the light's axis and the ray to the point;
// cone.xy as spot_cone() in lights.cpp packs them (exercise spot_cone), y = 0 for a hard edge at x.
float spot_factor(vec4 cone, float cos_theta) {
    if (cone.y <= 0.0) return cos_theta >= cone.x ? 1.0 : 0.0;  // no ramp to divide by: a hard edge
    return clamp((cos_theta - cone.x) * cone.y, 0.0, 1.0);
}

// The unit tangent for Ward: the mesh tangent made perpendicular to N (any ⟂ vector if it is parallel).
vec3 tangent_frame(vec3 N, vec3 tangent) {
    const vec3 any_perpendicular = normalize(cross(abs(N.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0), N));
    return safe_normalize(tangent - N * dot(N, tangent), any_perpendicular);
}

// Cook-Torrance pieces.
float distribution(float nh, float alpha) {
    const float a2 = alpha * alpha;
    if (DISTRIBUTION == 0) {  // GGX / Trowbridge-Reitz
        const float k = nh * nh * (a2 - 1.0) + 1.0;
        return a2 / (PI * k * k);
    }
    const float c = max(nh, MIN_COS_HALF), c2 = c * c;  // Beckmann
    return exp((c2 - 1.0) / (a2 * c2)) / (PI * a2 * c2 * c2);
}
float smith_g1(float x, float alpha) {
    if (DISTRIBUTION == 0) return 2.0 * x / (x + sqrt(alpha * alpha + (1.0 - alpha * alpha) * x * x));
    const float c = x / (alpha * max(sqrt(max(1.0 - x * x, 0.0)), 1e-7));  // Walter et al. 2007
    return c < 1.6 ? (3.535 * c + 2.181 * c * c) / (1.0 + 2.276 * c + 2.577 * c * c) : 1.0;
}

// The half vector H: the normal a mirror-like facet needs to reflect L into V (Blinn's highlight
// and the microfacet models use it). A highlight: how much of a light the surface sends towards
// the eye, from 0 to 1, as a cosine raised to the shininess n (the larger n, the sharper it is).
// EXERCISE blinn_phong: half_vector: which unit direction lies halfway between L and V, and what if L + V is zero? phong_highlight: where does L's mirror image about N point, and how closely does V follow it? blinn_highlight: how closely does N follow the half vector? Both highlights: clamped how, narrowed by n how? Read docs/lighting.md "Lighting models", "Numerical safety" (why power(), not pow(); safe_normalize()). Wrong: shiny materials look matte, the highlight covers the whole lit side or sits in the wrong place, toon highlights vanish. Checked by Lab2Term.BlinnPhongHighlights, Lab2Term.PhongHighlights, Lab2Render.DirectionalLight.
// STUB: vec3 half_vector(vec3 N, vec3 V, vec3 L) { return N; }  // every facet lined up with N
// STUB: float phong_highlight(vec3 N, vec3 V, vec3 L, float n) { return 0.0; }  // matte: no highlights
// STUB: float blinn_highlight(vec3 N, vec3 V, vec3 L, float n) { return 0.0; }  // matte: no highlights
vec3 half_vector(vec3 N, vec3 V, vec3 L) {
    const vec3 H = safe_normalize(L + V, N);  // N where L and V cancel
    check(H);
    return H;
}

float phong_highlight(vec3 N, vec3 V, vec3 L, float n) {
    const vec3 R = 2.0 * dot(N, L) * N - L;  // reflect(−L, N): L's mirror image about N
    return power(max(dot(R, V), 0.0), n);
}

float blinn_highlight(vec3 N, vec3 V, vec3 L, float n) {
    return power(max(dot(N, half_vector(N, V, L)), 0.0), n);
}
// END EXERCISE

// What one light contributes per unit radiance: albedo·diffuse + specular (docs/lighting.md).
vec3 reflectance(Material m, vec3 N, vec3 V, vec3 L, vec3 T) {
    const float nl = dot(N, L);
    check(nl);
    if (!(nl > 0.0)) return vec3(0.0);  // the light is behind the surface
    const vec3 a = m.albedo.rgb, s = m.specular.rgb;
    const float n = m.specular.a;
    const float nv = dot(N, V);

    if (LIGHTING_MODEL == MODEL_LAMBERT) return a * nl;
    if (LIGHTING_MODEL == MODEL_PHONG) {
        return a * nl + s * phong_highlight(N, V, L, n);
    }
    if (LIGHTING_MODEL == MODEL_TOON) {
        const float band = ceil(nl * float(TOON_BANDS)) / float(TOON_BANDS);
        return a * band + s * (blinn_highlight(N, V, L, n) > 0.5 ? 1.0 : 0.0);
    }
    vec3 diffuse = a * nl;  // Lambert, unless the model replaces it
    if (LIGHTING_MODEL == MODEL_OREN_NAYAR) {
        const float s2 = m.f0.a * m.f0.a;  // σ = roughness (radians)
        const float A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
        const float nvc = clamp(nv, 0.0, 1.0);
        const vec3 lp = L - N * nl, vp = V - N * nvc;
        const float lv = dot(lp, lp) * dot(vp, vp);
        const float cos_phi = lv > MIN_LENGTH2 ? dot(lp, vp) * inversesqrt(lv) : 0.0;
        const float cos_alpha = min(nl, nvc), cos_beta = max(nl, nvc);
        const float sin_alpha = sqrt(max(1.0 - cos_alpha * cos_alpha, 0.0));
        const float tan_beta = sqrt(max(1.0 - cos_beta * cos_beta, 0.0)) / cos_beta;
        diffuse = a * nl * (A + B * max(cos_phi, 0.0) * sin_alpha * tan_beta);
    }
    if (LIGHTING_MODEL == MODEL_MINNAERT) {
        const float k = m.params.z;
        diffuse = a * power(nl, k) * pow(max(nv, MIN_COS_VIEW), k - 1.0);
    }
    if (LIGHTING_MODEL == MODEL_COOK_TORRANCE) {
        const vec3 H = half_vector(N, V, L);
        const float nh = max(dot(N, H), 0.0);
        const float alpha = max(m.f0.a * m.f0.a, MIN_ALPHA);
        const float nvc = max(nv, MIN_COS_VIEW);
        const vec3 F = m.f0.rgb + (1.0 - m.f0.rgb) * pow(1.0 - clamp(dot(V, H), 0.0, 1.0), 5.0);
        const float G = smith_g1(nl, alpha) * smith_g1(nvc, alpha);
        // BRDF·N·L scaled by π so that its Lambert part is the lab's a·N·L.
        const vec3 spec = PI * distribution(nh, alpha) * G * F / (4.0 * nvc);
        check(spec);
        return diffuse + spec;
    }
    if (LIGHTING_MODEL == MODEL_WARD) {
        const vec3 H = half_vector(N, V, L);
        const float nh = max(dot(N, H), 0.0);
        const vec3 B = cross(N, T);
        const float ax = m.params.x, ay = m.params.y;
        const float hn = max(nh, MIN_COS_HALF);
        const float ht = dot(H, T) / ax, hb = dot(H, B) / ay;
        const float e = exp(-(ht * ht + hb * hb) / (hn * hn));
        const vec3 spec = s * nl * e / (4.0 * ax * ay * sqrt(nl * max(nv, MIN_COS_VIEW)));
        check(spec);
        return diffuse + spec;
    }
    // Blinn-Phong specular (also for Oren-Nayar and Minnaert, which only change the diffuse part).
    check(diffuse);
    return diffuse + s * blinn_highlight(N, V, L, n);
}

// The whole equation at world point P with unit normal N, unit view direction V and the
// (unnormalized) world tangent of the mesh.
vec3 shade(Material m, vec3 P, vec3 N, vec3 V, vec3 tangent) {
    vec3 color = m.emissive.rgb + frame.ambient.rgb * m.albedo.rgb;
    const vec3 T = LIGHTING_MODEL == MODEL_WARD ? tangent_frame(N, tangent) : vec3(0.0);
    for (int i = 0; i < DIRECTIONAL_COUNT; ++i) {
        const DirectionalLight light = lights.directional[i];
        color += light.radiance.rgb * reflectance(m, N, V, -light.direction.xyz, T);
    }
    for (int i = 0; i < POINT_COUNT; ++i) {
        const PointLight light = lights.point[i];
        const vec3 to_light = light.position.xyz - P;
        const float d = length(to_light);
        const vec3 L = safe_normalize(to_light, N);  // d = 0: the light is on the surface, L = N
        const float att = attenuation(light.attenuation.xyz, d);
        check(att);
        color += light.radiance.rgb * att * reflectance(m, N, V, L, T);
    }
    for (int i = 0; i < SPOT_COUNT; ++i) {
        const SpotLight light = lights.spot[i];
        const vec3 to_light = light.position.xyz - P;
        const float d = length(to_light);
        const vec3 L = safe_normalize(to_light, N);
        const float att = attenuation(light.attenuation.xyz, d) * spot_factor(light.cone, dot(-L, light.direction.xyz));
        check(att);
        color += light.radiance.rgb * att * reflectance(m, N, V, L, T);
    }
    check(color);
    return color;
}
