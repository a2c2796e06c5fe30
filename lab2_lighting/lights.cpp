#include "lights.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace {
constexpr double kPi = 3.14159265358979323846;
double cos_deg(double deg) { return std::cos(deg * kPi / 180.0); }

// Below this width the ramp of a spot cone is a hard edge (no division by ~0).
constexpr double kMinConeWidth = 1e-6;

glm::vec3 unit_or(const glm::vec3& v, const glm::vec3& fallback) {
    const double len = glm::length(glm::dvec3(v));
    return len > 1e-12 ? glm::vec3(glm::dvec3(v) / len) : fallback;
}

const char* const kModels[] = {"Lambert", "Phong", "Blinn-Phong", "Toon / cel", "Oren-Nayar", "Minnaert",
                               "Cook-Torrance", "Ward (anisotropic)"};
const char* const kShadings[] = {"Flat (per triangle)", "Gouraud (per vertex)", "Phong (per pixel)"};
const char* const kFalloffs[] = {"smooth (inner..outer)", "edge 1-(1-cos b)/(1-cos a)"};
const char* const kDistributions[] = {"GGX", "Beckmann"};
const char* const kTypes[] = {"directional", "point", "spot"};
}  // namespace

glm::vec2 spot_cone(const lab::LightDesc& light, lab::LightingDesc::SpotFalloff falloff) {
    const double cos_outer = cos_deg(light.outer_deg);
    const double cos_start = falloff == lab::LightingDesc::SpotFalloff::Edge ? 1.0 : cos_deg(light.inner_deg);
    const double width = cos_start - cos_outer;
    return {float(cos_outer), width >= kMinConeWidth ? float(1.0 / width) : 0.0f};
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
        throw std::runtime_error(scene.file + ": lab 2 supports at most " + std::to_string(kMaxMaterials) +
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
        out[i] = {glm::vec4(m.albedo, 1.0f), glm::vec4(m.specular, m.shininess), glm::vec4(m.emissive, 0.0f),
                  glm::vec4(m.f0, m.roughness), glm::vec4(m.roughness_x, m.roughness_y, m.minnaert_k, 0.0f)};
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
            l.options.toon_bands};
}

namespace {
bool combo(const char* label, int& value, const char* const* items, int count) {
    return ImGui::Combo(label, &value, items, count);
}

template <typename Enum>
void enum_combo(const char* label, Enum& value, const char* const* items, int count) {
    int v = int(value);
    if (combo(label, v, items, count)) value = Enum(v);
}

void edit_light(lab::LightDesc& l) {
    const bool directional = l.type == lab::LightDesc::Type::Directional;
    const bool spot = l.type == lab::LightDesc::Type::Spot;
    if (!directional) ImGui::DragFloat3("position", &l.position.x, 0.05f);
    if (directional || spot) {
        glm::vec3 d = l.direction;
        if (ImGui::DragFloat3("direction", &d.x, 0.01f) && glm::length(d) >= 1e-6f) l.direction = d;
    }
    ImGui::ColorEdit3("color", &l.color.x, ImGuiColorEditFlags_Float);
    ImGui::DragFloat("intensity", &l.intensity, 0.01f, 0.0f, 1e6f, "%.3f", ImGuiSliderFlags_Logarithmic);
    if (!directional) ImGui::DragFloat3("attenuation c,l,q", &l.attenuation.x, 0.005f, 0.0f, 1e6f, "%.3f");
    if (spot) {
        ImGui::SliderFloat("inner", &l.inner_deg, 0.0f, 90.0f, "%.1f deg");
        ImGui::SliderFloat("outer", &l.outer_deg, 0.0f, 90.0f, "%.1f deg");
    }
    // Keep the values the loader would accept.
    l.intensity = std::max(l.intensity, 0.0f);
    l.attenuation = glm::max(l.attenuation, glm::vec3(0.0f));
    l.color = glm::max(l.color, glm::vec3(0.0f));
    l.inner_deg = std::min(l.inner_deg, l.outer_deg);
}

void edit_material(lab::MaterialDesc& m, lab::LightingDesc::Model model) {
    using M = lab::LightingDesc::Model;
    ImGui::ColorEdit3("albedo", &m.albedo.x, ImGuiColorEditFlags_Float);
    ImGui::ColorEdit3("specular", &m.specular.x, ImGuiColorEditFlags_Float);
    ImGui::ColorEdit3("emissive", &m.emissive.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
    ImGui::DragFloat("shininess", &m.shininess, 0.5f, 0.0f, 10000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
    if (model == M::OrenNayar || model == M::CookTorrance) ImGui::SliderFloat("roughness", &m.roughness, 0.0f, 1.0f);
    if (model == M::CookTorrance) ImGui::ColorEdit3("F0", &m.f0.x, ImGuiColorEditFlags_Float);
    if (model == M::Ward) {
        ImGui::SliderFloat("roughness x", &m.roughness_x, 0.01f, 1.0f);
        ImGui::SliderFloat("roughness y", &m.roughness_y, 0.01f, 1.0f);
    }
    if (model == M::Minnaert) ImGui::SliderFloat("Minnaert k", &m.minnaert_k, 0.0f, 4.0f);
    m.shininess = std::max(m.shininess, 0.0f);
    m.f0 = glm::clamp(m.f0, glm::vec3(0.0f), glm::vec3(1.0f));
}
}  // namespace

void lighting_panel(Lighting& l) {
    using Type = lab::LightDesc::Type;
    // Top right, clear of the camera panel, the first time the window appears.
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 390.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("Lighting");
    enum_combo("lighting model", l.options.model, kModels, 8);
    enum_combo("shading", l.options.shading, kShadings, 3);
    enum_combo("spot falloff", l.options.spot_falloff, kFalloffs, 2);
    if (l.options.model == lab::LightingDesc::Model::CookTorrance)
        enum_combo("distribution", l.options.distribution, kDistributions, 2);
    if (l.options.model == lab::LightingDesc::Model::Toon) ImGui::SliderInt("toon bands", &l.options.toon_bands, 1, 16);
    ImGui::Checkbox("light markers", &l.options.markers);

    if (ImGui::CollapsingHeader("Ambient", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::ColorEdit3("ambient color", &l.ambient.color.x, ImGuiColorEditFlags_Float);
        ImGui::DragFloat("ambient intensity", &l.ambient.intensity, 0.005f, 0.0f, 100.0f);
        l.ambient.intensity = std::max(l.ambient.intensity, 0.0f);
    }

    if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) {
        const int limits[3] = {kMaxDirectional, kMaxPoint, kMaxSpot};
        for (int t = 0; t < 3; ++t) {
            if (t > 0) ImGui::SameLine();
            const bool full = l.count(Type(t)) >= limits[t];
            if (full) ImGui::BeginDisabled();
            if (ImGui::Button((std::string("+ ") + kTypes[t]).c_str())) {
                lab::LightDesc light;
                light.type = Type(t);
                light.position = {0.0f, 2.0f, 0.0f};
                light.attenuation = t == 0 ? glm::vec3(1, 0, 0) : glm::vec3(1.0f, 0.09f, 0.032f);
                l.lights.push_back(light);
            }
            if (full) ImGui::EndDisabled();
        }
        ImGui::Text("%d directional, %d point, %d spot", l.count(Type::Directional), l.count(Type::Point),
                    l.count(Type::Spot));
        for (size_t i = 0; i < l.lights.size(); ++i) {
            ImGui::PushID(int(i));
            const bool open = ImGui::TreeNode("light", "%s %zu", kTypes[int(l.lights[i].type)], i);
            ImGui::SameLine();
            const bool remove = ImGui::SmallButton("remove");
            if (open) {
                edit_light(l.lights[i]);
                ImGui::TreePop();
            }
            ImGui::PopID();
            if (remove) {
                l.lights.erase(l.lights.begin() + long(i));
                break;
            }
        }
    }

    if (ImGui::CollapsingHeader("Materials")) {
        for (size_t i = 0; i < l.materials.size(); ++i) {
            ImGui::PushID(int(i));
            if (ImGui::TreeNode("material", "%s", l.material_names[i].c_str())) {
                edit_material(l.materials[i], l.options.model);
                ImGui::TreePop();
            }
            ImGui::PopID();
        }
    }
    ImGui::End();
}
