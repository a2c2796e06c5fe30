#include "lighting_panel.h"

#include "ui_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace {
const char* const kModels[] = {"Lambert", "Phong", "Blinn-Phong", "Toon / cel", "Oren-Nayar", "Minnaert",
                               "Cook-Torrance", "Ward (anisotropic)"};
const char* const kShadings[] = {"Flat (per triangle)", "Gouraud (per vertex)", "Phong (per pixel)"};
const char* const kFalloffs[] = {"smooth (inner..outer)", "edge 1-(1-cos b)/(1-cos a)"};
const char* const kDistributions[] = {"GGX", "Beckmann"};

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
    ImGui::TextDisabled("R (or saving the scene file) reloads it:\nthe file's values replace these edits.");
    lab::ui::enum_combo("lighting model", l.options.model, kModels, 8);
    lab::ui::enum_combo("shading", l.options.shading, kShadings, 3);
    lab::ui::enum_combo("spot falloff", l.options.spot_falloff, kFalloffs, 2);
    if (l.options.model == lab::LightingDesc::Model::CookTorrance)
        lab::ui::enum_combo("distribution", l.options.distribution, kDistributions, 2);
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
            if (ImGui::Button((std::string("+ ") + lab::light_type_name(Type(t))).c_str())) {
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
            const bool open = ImGui::TreeNode("light", "%s %zu", lab::light_type_name(l.lights[i].type), i);
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
