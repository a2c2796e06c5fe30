// lights.h — the lights and lighting models on the CPU side (since lab 2):
//  * Lighting: what the scene file says and the UI edits (ambient, lights, models, materials);
//  * the buffer layouts the shaders read (lights: storage, materials: uniform; must match
//    lighting.glsl in this lab's shader folder);
//  * Variant: the specialization constants that pick a pipeline variant (model, shading, the
//    number of lights of each type), so a scene pays only for the lights and the model it uses.
// Lab 4: which lights cast shadows (a shadow slot each) and how their maps are read.
// The panel that edits all this is in lighting_panel.h (lab 4's shadow settings: shadows_panel.h).
// The equation itself is in docs/lighting.md and lighting.glsl.
#pragma once

#include "scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

constexpr int kMaxDirectional = 8;
constexpr int kMaxPoint = 32;
constexpr int kMaxSpot = 32;
// Lab 4: shadow-casting lights, each with its own map and specialization constants (lighting.glsl).
constexpr int kMaxShadowLights = 4;

// --- GPU layouts (every member a vec4, so C++ and GLSL agree without padding rules, std140 = std430) ---
struct GpuDirectional {
    glm::vec4 direction;  // xyz: unit vector, the way the light travels
    glm::vec4 radiance;   // rgb: color × intensity
};
struct GpuPoint {
    glm::vec4 position;
    glm::vec4 radiance;
    glm::vec4 attenuation;  // xyz: constant, linear, quadratic
};
struct GpuSpot {
    glm::vec4 position;
    glm::vec4 direction;  // xyz: unit vector
    glm::vec4 radiance;
    glm::vec4 attenuation;
    glm::vec4 cone;  // xy: spot_cone()
};
struct GpuLights {
    glm::uvec4 counts;  // x: directional, y: point, z: spot
    GpuDirectional directional[kMaxDirectional];
    GpuPoint point[kMaxPoint];
    GpuSpot spot[kMaxSpot];
};
// The lights are a uniform buffer, not a storage buffer: every pixel reads every light, and on a
// CPU rasterizer (lavapipe) a storage buffer is read lane by lane, a uniform one once for all
// (README, "What it costs"). A uniform buffer may hold 16 KB on every device (maxUniformBufferRange):
static_assert(sizeof(GpuLights) <= 16384, "the lights no longer fit a uniform buffer: use a storage buffer");
// The materials are a uniform buffer of kMaxMaterials entries (std140 = std430 here: all vec4).
constexpr int kMaxMaterials = 128;
struct GpuMaterial {
    glm::vec4 albedo;    // rgb, a: opacity (lab 4)
    glm::vec4 specular;  // rgb: specular color, a: shininess
    glm::vec4 emissive;  // rgb
    glm::vec4 f0;        // rgb: Cook-Torrance F0, a: roughness
    glm::vec4 params;    // x: Ward roughness along the tangent, y: along the bitangent, z: Minnaert k
    glm::vec4 uv_transform;   // xy: uv_scale, zw: uv_offset (reduced by whole repeats, see pack_materials)
    // amplitude, frequency | position_frequency, scales | weights, emissive_strength | two more
    // vec4s: what the whole repeats taken out of uv_offset change in the distortion, see pack_materials
    glm::vec4 distortion[5];
};

// The spot cone as the shader reads it (spot_factor() in lighting.glsl): two numbers per light,
// worked out once here so that each pixel pays one subtraction, one multiply and a clamp
// (exercise spot_cone).
glm::vec2 spot_cone(const lab::LightDesc& light, lab::LightingDesc::SpotFalloff falloff);

// Everything the lighting panel can change.
struct Lighting {
    lab::AmbientDesc ambient;
    std::vector<lab::LightDesc> lights;
    lab::LightingDesc options;
    std::vector<std::string> material_names;  // the scene's materials, in name order
    std::vector<lab::MaterialDesc> materials;
    bool mip_view = false;  // lab 3: tint textured pixels by the mip level they read
    bool animate_lights = false;  // lab 4: lights circle the scene's Y axis (what a moving light costs)
    int shadow_view = -1;         // lab 4: the light whose shadow map is shown (−1: none)
    int translucent_layers = 0;  // lab 4: a shadow caster is translucent: the maps' layers K (translucent_shadows.h), else 0

    static Lighting from_scene(const lab::Scene& scene);
    // Lab 4: is the object's mesh convex (a ray crosses at most one of its front faces)? The
    // primitives but the torus; an OBJ model is not assumed to be.
    static bool convex(const lab::ObjectDesc& object) { return object.mesh_path.empty() && object.mesh != "torus"; }
    int material_index(const std::string& name) const;
    int count(lab::LightDesc::Type type) const;
    // Lab 4: each light's shadow slot: the first kMaxShadowLights lights with cast_shadows, −1 for the others.
    std::vector<int> shadow_slots() const;

    glm::vec4 ambient_radiance() const;  // rgb: ambient color × intensity, a: 0
    GpuLights pack_lights() const;
    // Writes the materials into `out` (kMaxMaterials entries; the mapped uniform buffer).
    void pack_materials(GpuMaterial* out) const;
};

// The specialization constants by constant_id (lighting.glsl): variant[constant::shading] is constant_id 1.
namespace constant { enum : size_t { model, shading, directional_count, point_count, spot_count, distribution,
                                     nan_check, toon_bands,
                                     // lab 3, per material (variant_of leaves them 0; the renderer sets them per draw)
                                     albedo_map, specular_map, emissive_map, distorted_sampling, probes, mip_view,
                                     // lab 4, per shadow slot s: shadows + 5s map kind (0 none, 1 2D, 2 cube),
                                     // + 1 PCF kernel N, + 2 filter (0 nearest, 1 bilinear), + 3 translucent layers K (0: none),
                                     // + 4 the light it belongs to (shadow_light_id, −1: none)
                                     shadows, count = shadows + 5 * kMaxShadowLights }; }
// Lab 4: how the shaders name the k-th light of a type (0 directional, 1 point, 2 spot) in a slot's
// constant: LIGHT_ID in shadows.glsl. Fixed at pipeline creation, so every lookup is picked there.
constexpr int32_t shadow_light_id(int type, int k) { return type * 64 + k; }
using Variant = std::array<int32_t, constant::count>;
Variant variant_of(const Lighting& lighting);
