#include "textures_panel.h"

#include "ui_widgets.h"

#include <imgui.h>

#include <algorithm>

namespace {
const char* const kFilters[] = {"nearest", "linear"};
const char* const kMipmaps[] = {"none", "nearest", "linear"};
const char* const kWraps[] = {"repeat", "clamp", "mirror"};
const char* const kAnisotropic[] = {"sampler", "probes", "auto"};

// A map path or "procedural:NAME"; Enter applies it, an empty field removes the map, an unknown
// procedural name is ignored (a scene file would be rejected).
bool edit_map(const char* label, std::string& map) {
    std::string value = map;
    if (!lab::ui::edit_on_enter(label, value) || !lab::known_procedural_or_path(value)) return false;
    map = value;
    return true;
}
}  // namespace

bool textures_panel(Lighting& l, const std::vector<std::string>& warnings, const std::string& auto_choice,
                    float frame_ms) {
    ImGui::SetNextWindowPos(ImVec2(10.0f, ImGui::GetIO().DisplaySize.y - 300.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380.0f, 290.0f), ImGuiCond_FirstUseEver);  // below the Camera panel at 720 px
    ImGui::Begin("Textures");
    ImGui::Text("%.2f ms/frame", frame_ms);
    bool rebuild = ImGui::Checkbox("mip-level view", &l.mip_view);
    ImGui::TextDisabled("level 0 white, 1 red, 2 yellow, 3 green, 4 cyan, 5 blue, 6+ magenta");
    for (const std::string& warning : warnings) ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f), "%s", warning.c_str());
    for (size_t i = 0; i < l.materials.size(); ++i) {
        lab::MaterialDesc& m = l.materials[i];
        ImGui::PushID(int(i));
        if (ImGui::TreeNode("material", "%s%s", l.material_names[i].c_str(), m.has_maps() ? "" : " (no maps)")) {
            rebuild |= edit_map("albedo map", m.albedo_map);
            rebuild |= edit_map("specular map", m.specular_map);
            rebuild |= edit_map("emissive map", m.emissive_map);
            ImGui::DragFloat("emissive strength", &m.emissive_strength, 0.01f, 0.0f, 100.0f);
            ImGui::DragFloat2("uv scale", &m.uv_scale.x, 0.01f);
            ImGui::DragFloat2("uv offset", &m.uv_offset.x, 0.01f);
            rebuild |= lab::ui::enum_combo("filter", m.sampler.filter, kFilters, 2);
            rebuild |= lab::ui::enum_combo("mipmaps", m.sampler.mipmaps, kMipmaps, 3);
            rebuild |= ImGui::SliderInt("anisotropy", &m.sampler.anisotropy, 1, 16);
            rebuild |= lab::ui::enum_combo("anisotropic by", m.sampler.anisotropic, kAnisotropic, 3);
            if (m.sampler.anisotropic == lab::SamplerDesc::Anisotropic::Auto) ImGui::TextDisabled("%s", auto_choice.c_str());
            if (m.sampler.anisotropic != lab::SamplerDesc::Anisotropic::Sampler && m.sampler.mipmaps == lab::SamplerDesc::Mipmaps::None)
                ImGui::TextDisabled("probes need mipmaps: plain lookups");
            rebuild |= lab::ui::enum_combo("wrap", m.sampler.wrap, kWraps, 3);
            rebuild |= ImGui::Checkbox("distorted sampling (albedo)", &m.distorted);
            if (m.distorted) {
                ImGui::DragFloat2("amplitude", &m.distortion.amplitude.x, 0.001f, -1.0f, 1.0f);
                ImGui::DragFloat2("frequency", &m.distortion.frequency.x, 0.1f);
                ImGui::DragFloat2("position frequency", &m.distortion.position_frequency.x, 0.05f);
                ImGui::DragFloat2("scales", &m.distortion.scales.x, 0.01f);
                ImGui::SliderFloat2("weights", &m.distortion.weights.x, 0.0f, 1.0f);
            }
            // Keep the values the loader would accept.
            m.emissive_strength = std::max(m.emissive_strength, 0.0f);
            m.sampler.anisotropy = std::clamp(m.sampler.anisotropy, 1, 16);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    ImGui::End();
    return rebuild;
}
