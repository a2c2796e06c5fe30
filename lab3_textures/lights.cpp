#include "lights.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace {
constexpr double kPi = 3.14159265358979323846;
[[maybe_unused]] double cos_deg(double deg) { return std::cos(deg * kPi / 180.0); }

// Below this width the ramp of a spot cone is a hard edge (no division by ~0).
[[maybe_unused]] constexpr double kMinConeWidth = 1e-6;

glm::vec3 unit_or(const glm::vec3& v, const glm::vec3& fallback) {
    const double len = glm::length(glm::dvec3(v));
    return len > 1e-12 ? glm::vec3(glm::dvec3(v) / len) : fallback;
}
}  // namespace

glm::vec2 spot_cone(const lab::LightDesc& light, lab::LightingDesc::SpotFalloff falloff) {
    // EXERCISE spot_cone: the two numbers spot_factor() in lighting.glsl reads, so that its one subtraction, multiply and clamp per pixel give docs/lighting.md's cone: full light inside inner_deg, none outside outer_deg, a ramp linear in cos between. Which cosine is where the ramp ends, which its slope, and what does "edge" falloff make of the ramp (write its X as a ramp in cos β)? When is a ramp too narrow to divide by (kMinConeWidth), and what must y be then? Why in double? Read docs/lighting.md "Light types", "Numerical safety", spot_factor(). Wrong: a spot lighting all around, a hard-edged spot where the edge should fade, light outside the cone, or "edge" looking like "smooth". Checked by SpotFactor.LabPacksTheSameCone, Lab2Term.SpotCones, Lab2Render.SpotLights.
    // STUB: (void)light, (void)falloff;
    // STUB: return {-1.0f, 0.0f};  // a hard edge at cos = −1: the spot shines in every direction
    const double cos_outer = cos_deg(light.outer_deg);
    const double cos_start = falloff == lab::LightingDesc::SpotFalloff::Edge ? 1.0 : cos_deg(light.inner_deg);
    const double width = cos_start - cos_outer;
    return {float(cos_outer), width >= kMinConeWidth ? float(1.0 / width) : 0.0f};
    // END EXERCISE
}

Lighting Lighting::from_scene(const lab::Scene& scene) {
    Lighting l;
    l.ambient = scene.ambient;
    l.lights = scene.lights;
    l.options = scene.lighting;
    for (const auto& [name, material] : scene.materials) {
        l.material_names.push_back(name);
        l.materials.push_back(material);
    }
    if (l.materials.size() > size_t(kMaxMaterials))
        throw std::runtime_error(scene.file + ": at most " + std::to_string(kMaxMaterials) +
                                 " materials, the scene has " + std::to_string(l.materials.size()));
    // The GPU arrays have fixed sizes: extra lights of a type are dropped (with a note).
    int kept[3] = {0, 0, 0};
    const int limit[3] = {kMaxDirectional, kMaxPoint, kMaxSpot};
    std::vector<lab::LightDesc> lights;
    for (const lab::LightDesc& light : l.lights)
        if (kept[int(light.type)]++ < limit[int(light.type)]) lights.push_back(light);
    if (lights.size() < l.lights.size())
        std::fprintf(stderr, "warning: at most %d directional, %d point and %d spot lights: %zu ignored\n",
                     kMaxDirectional, kMaxPoint, kMaxSpot, l.lights.size() - lights.size());
    l.lights = lights;
    return l;
}

int Lighting::material_index(const std::string& name) const {
    return int(std::find(material_names.begin(), material_names.end(), name) - material_names.begin());
}

int Lighting::count(lab::LightDesc::Type type) const {
    return int(std::count_if(lights.begin(), lights.end(), [type](const lab::LightDesc& l) { return l.type == type; }));
}

glm::vec4 Lighting::ambient_radiance() const {
    // color × intensity in double, rounded once.
    return glm::vec4(glm::dvec3(ambient.color) * double(ambient.intensity), 0.0);
}

GpuLights Lighting::pack_lights() const {
    GpuLights g{};
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    for (const lab::LightDesc& l : lights) {
        const glm::vec4 radiance(glm::dvec3(l.color) * double(l.intensity), 0.0);
        const glm::vec4 attenuation(l.attenuation, 0.0f);
        switch (l.type) {
            case lab::LightDesc::Type::Directional:
                if (g.counts.x < kMaxDirectional)
                    g.directional[g.counts.x++] = {glm::vec4(unit_or(l.direction, down), 0.0f), radiance};
                break;
            case lab::LightDesc::Type::Point:
                if (g.counts.y < kMaxPoint) g.point[g.counts.y++] = {glm::vec4(l.position, 1.0f), radiance, attenuation};
                break;
            case lab::LightDesc::Type::Spot:
                if (g.counts.z < kMaxSpot)
                    g.spot[g.counts.z++] = {glm::vec4(l.position, 1.0f), glm::vec4(unit_or(l.direction, down), 0.0f),
                                            radiance, attenuation,
                                            glm::vec4(spot_cone(l, options.spot_falloff), 0.0f, 0.0f)};
                break;
        }
    }
    return g;
}

void Lighting::pack_materials(GpuMaterial* out) const {
    // Straight into the mapped buffer: nothing is allocated per frame. Unused entries keep
    // whatever they held; no object indexes them.
    const size_t n = std::min(materials.size(), size_t(kMaxMaterials));
    for (size_t i = 0; i < n; ++i) {
        const lab::MaterialDesc& m = materials[i];
        // A float has ~7 digits: uv + 1e6 would keep no fraction at all. Whole repeats of the
        // offset change nothing (period 1 for repeat, 2 for mirror), so they go here, in double.
        const double period = m.sampler.wrap == lab::SamplerDesc::Wrap::Mirror ? 2.0 : 1.0;
        const glm::dvec2 offset = m.sampler.wrap == lab::SamplerDesc::Wrap::Clamp
                                      ? glm::dvec2(m.uv_offset)
                                      : glm::mod(glm::dvec2(m.uv_offset), period);
        const lab::DistortionDesc& d = m.distortion;
        // Distorted sampling sees the whole offset: its wobble and its scaled lookups have periods
        // of their own, so the whole repeats taken out above still change them. distortion[3] and
        // [4] carry that change, worked out and reduced here in double so that a huge uv_offset
        // keeps its precision; how the shader uses them is the exercise distorted_uv.
        const glm::dvec2 whole = glm::dvec2(m.uv_offset) - offset;
        const glm::dvec2 phase = glm::mod(glm::dvec2(d.frequency) * glm::dvec2(whole.y, whole.x), 2.0 * kPi);
        const glm::dvec2 shift1 = glm::mod(double(d.scales.x) * whole, period), shift2 = glm::mod(double(d.scales.y) * whole, period);
        out[i] = {glm::vec4(m.albedo, 1.0f), glm::vec4(m.specular, m.shininess), glm::vec4(m.emissive, 0.0f),
                  glm::vec4(m.f0, m.roughness), glm::vec4(m.roughness_x, m.roughness_y, m.minnaert_k, 0.0f),
                  glm::vec4(m.uv_scale, glm::vec2(offset)),
                  {glm::vec4(d.amplitude, d.frequency), glm::vec4(d.position_frequency, d.scales),
                   glm::vec4(d.weights, m.emissive_strength, 0.0f), glm::vec4(glm::vec2(phase), 0.0f, 0.0f),
                   glm::vec4(glm::vec2(shift1), glm::vec2(shift2))}};
    }
}

Variant variant_of(const Lighting& l) {
    return {int32_t(l.options.model),
            int32_t(l.options.shading),
            std::min(l.count(lab::LightDesc::Type::Directional), kMaxDirectional),
            std::min(l.count(lab::LightDesc::Type::Point), kMaxPoint),
            std::min(l.count(lab::LightDesc::Type::Spot), kMaxSpot),
            int32_t(l.options.distribution),
            int32_t(l.options.nan_check),
            l.options.toon_bands,
            0, 0, 0, 0, 0,  // the material's maps and probes: Renderer fills them in per draw
            int32_t(l.mip_view)};
}
