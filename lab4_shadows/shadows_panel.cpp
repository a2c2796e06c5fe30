#include "shadows_panel.h"

#include "ui_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace {
const char* const kFilters[] = {"nearest", "bilinear"};
const int kResolutions[] = {1, 64, 128, 256, 512, 1024, 2048, 4096, 8192};
}  // namespace

void shadows_panel(Lighting& l, float frame_ms, int renders, const std::string& drawn, const std::string& translucent_layers) {
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 390.0f, ImGui::GetIO().DisplaySize.y - 330.0f),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380.0f, 320.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("Shadows");
    ImGui::Text("%.2f ms/frame, %d shadow map%s drawn last frame", frame_ms, renders, renders == 1 ? "" : "s");
    if (!drawn.empty()) ImGui::TextWrapped("texels per side drawn: %s", drawn.c_str());
    if (!translucent_layers.empty()) ImGui::TextWrapped("%s", translucent_layers.c_str());
    ImGui::Checkbox("animate lights", &l.animate_lights);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every light circles the Y axis: its map is rendered every frame");
    // The shadow-map view: one light's map (a point light's six faces) in the bottom right.
    const auto name = [&](int i) {
        return i < 0 || i >= int(l.lights.size()) ? std::string("none")
                                                  : std::string(lab::light_type_name(l.lights[size_t(i)].type)) + " " + std::to_string(i);
    };
    if (ImGui::BeginCombo("shadow-map view", name(l.shadow_view).c_str())) {
        for (int i = -1; i < int(l.lights.size()); ++i)  // none, then the lights that cast shadows
            if ((i < 0 || l.lights[size_t(i)].cast_shadows) && ImGui::Selectable(name(i).c_str(), std::max(l.shadow_view, -1) == i))
                l.shadow_view = i;
        ImGui::EndCombo();
    }
    for (size_t i = 0; i < l.lights.size(); ++i) {
        lab::LightDesc& light = l.lights[i];
        ImGui::PushID(int(i));
        ImGui::Checkbox("##casts", &light.cast_shadows);
        ImGui::SameLine();
        if (ImGui::TreeNode("light", "%s %zu casts shadows", lab::light_type_name(light.type), i)) {
            lab::ShadowDesc& s = light.shadow;
            if (ImGui::BeginCombo("resolution", std::to_string(s.resolution).c_str())) {
                for (int r : kResolutions)
                    if (ImGui::Selectable(std::to_string(r).c_str(), s.resolution == r)) s.resolution = r;
                ImGui::EndCombo();
            }
            ImGui::Checkbox("fit to view", &s.fit_to_view);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Draw about one texel per pixel of the picture, at most the resolution (README \"Maps sized to the picture\")");
            ImGui::SliderInt("PCF N (N x N taps)", &s.pcf, 1, 15);
            s.pcf = std::clamp(s.pcf | 1, 1, 15);  // odd: the kernel has a centre tap
            lab::ui::enum_combo("filter", s.filter, kFilters, 2);
            ImGui::DragFloat("depth bias", &s.bias, 1.0f, 0.0f, 1e7f, "%.1f", ImGuiSliderFlags_Logarithmic);
            ImGui::DragFloat("slope bias", &s.slope_bias, 0.05f, 0.0f, 100.0f, "%.2f");
            ImGui::DragFloat("normal offset (texels)", &s.normal_offset, 0.05f, 0.0f, 100.0f, "%.2f");
            // Keep the values the loader would accept.
            s.bias = std::max(s.bias, 0.0f);
            s.slope_bias = std::max(s.slope_bias, 0.0f);
            s.normal_offset = std::max(s.normal_offset, 0.0f);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    ImGui::End();
}
