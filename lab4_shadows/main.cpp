// Lab 4 — shadows.
//
// Lab 3's textured scene with shadows: each shadow-casting light renders a shadow map
// (directional: fitted orthographic, spot: perspective, point: cube) before the camera's
// pass, which reads it with PCF; translucent objects let 1 − opacity of the light through, and in
// the camera's pass their layers are sorted per pixel and blended over the others in depth order
// (translucent_layers.h: per-pixel lists, cleared before the pass, composed at its end). The
// "Shadows" panel edits it all live, shows a light's map and animates the lights
// (--dev-animate-lights does that headless, for --benchmark). The Vulkan half is here too: the
// shadow pass's render pass, images and comparison sampler in offscreen.cpp, its pipelines in
// shadow_maps.cpp. The rest (the Vulkan context, window, UI, scene file, image loading) comes
// from common/.
//
// Controls: W/S forward/back, A/D strafe, Space/Shift up/down (world Y),
// left-drag rotates (Look-At: orbits the target), wheel changes the distance
// to the target (Look-At), C switches the camera mode, R reloads the scene
// (it also reloads by itself when the file changes; the camera stays put).
#include "camera.h"
#include "lighting_panel.h"
#include "lights.h"
#include "renderer.h"
#include "shadows_panel.h"
#include "textures_panel.h"

#include "lab_app.h"
#include "run_lab.h"
#include "scene_reloader.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace {

struct Controls {
    double move_speed = 3.0;        // world units per second
    double degrees_per_pixel = 0.25;
};

void update_camera(lab::LabApp& app, Camera& camera, const Controls& controls, float dt) {
    if (app.key_pressed(GLFW_KEY_C))
        camera.set_mode(camera.mode == Camera::Mode::LookAt ? Camera::Mode::Transform : Camera::Mode::LookAt);

    // Keyboard: move along the view direction, the camera's right, and world up.
    const double step = controls.move_speed * dt;
    glm::dvec3 offset(0.0);
    if (app.key_down(GLFW_KEY_W)) offset += camera.forward() * step;
    if (app.key_down(GLFW_KEY_S)) offset -= camera.forward() * step;
    if (app.key_down(GLFW_KEY_D)) offset += camera.right() * step;
    if (app.key_down(GLFW_KEY_A)) offset -= camera.right() * step;
    if (app.key_down(GLFW_KEY_SPACE)) offset.y += step;
    if (app.key_down(GLFW_KEY_LEFT_SHIFT)) offset.y -= step;
    if (offset != glm::dvec3(0.0)) camera.move(offset);

    // Mouse: dragging right turns right (negative yaw), dragging up looks up.
    const lab::MouseInput& mouse = app.mouse();
    if (mouse.left_down && mouse.delta != glm::vec2(0.0f))
        camera.rotate(-mouse.delta.x * controls.degrees_per_pixel, -mouse.delta.y * controls.degrees_per_pixel);
    if (mouse.scroll != 0.0f) camera.zoom(mouse.scroll);
}

// Lab 4: turns every light about the world Y axis through the origin by 0.5 rad per second.
void animate_lights(Lighting& lighting, float dt) {
    const double angle = 0.5 * double(dt), c = std::cos(angle), s = std::sin(angle);
    const auto turn = [&](glm::vec3& v) { v = glm::vec3(glm::dvec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z)); };
    for (lab::LightDesc& light : lighting.lights) {
        turn(light.position);
        turn(light.direction);
    }
}

void camera_panel(lab::LabApp& app, Camera& camera, Controls& controls, const lab::SceneReloader& reloader) {
    ImGui::SetNextWindowSize(ImVec2(380.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("Camera");
    app.frame_stats_ui();  // frame time, "continuous rendering" checkbox
    ImGui::TextDisabled("scene: %s (R reloads)", reloader.file().c_str());
    if (!reloader.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", reloader.error().c_str());
        ImGui::PopStyleColor();
    }
    int mode = camera.mode == Camera::Mode::LookAt ? 0 : 1;
    if (ImGui::RadioButton("Look-At", &mode, 0)) camera.set_mode(Camera::Mode::LookAt);
    ImGui::SameLine();
    if (ImGui::RadioButton("Transform", &mode, 1)) camera.set_mode(Camera::Mode::Transform);
    ImGui::SameLine();
    ImGui::TextDisabled("(C)");

    if (camera.mode == Camera::Mode::LookAt) {
        ImGui::InputScalarN("eye", ImGuiDataType_Double, &camera.eye.x, 3, nullptr, nullptr, "%.3f");
        ImGui::InputScalarN("target", ImGuiDataType_Double, &camera.target.x, 3, nullptr, nullptr, "%.3f");
        ImGui::InputScalarN("up", ImGuiDataType_Double, &camera.up.x, 3, nullptr, nullptr, "%.3f");
        ImGui::Text("distance %.3f", glm::length(camera.eye - camera.target));
    } else {
        ImGui::InputScalarN("position", ImGuiDataType_Double, &camera.position.x, 3, nullptr, nullptr, "%.3f");
        const double lo = -180.0, hi = 180.0, pitch_lo = -90.0, pitch_hi = 90.0;
        ImGui::SliderScalar("yaw", ImGuiDataType_Double, &camera.yaw_deg, &lo, &hi, "%.1f deg");
        ImGui::SliderScalar("pitch", ImGuiDataType_Double, &camera.pitch_deg, &pitch_lo, &pitch_hi, "%.1f deg");
        ImGui::SliderScalar("roll", ImGuiDataType_Double, &camera.roll_deg, &lo, &hi, "%.1f deg");
    }
    const double fov_lo = 1.0, fov_hi = 179.0;
    ImGui::SliderScalar("fov y", ImGuiDataType_Double, &camera.fov_y_deg, &fov_lo, &fov_hi, "%.1f deg");
    ImGui::InputDouble("near", &camera.near_plane, 0.0, 0.0, "%.4f");
    ImGui::InputDouble("far", &camera.far_plane, 0.0, 0.0, "%.1f");
    // Keep the projection valid whatever is typed: 0 < near < far.
    camera.near_plane = std::max(camera.near_plane, 1e-6);
    camera.far_plane = std::max(camera.far_plane, camera.near_plane * 1.001);

    const double speed_lo = 0.1, speed_hi = 50.0;
    ImGui::SliderScalar("move speed", ImGuiDataType_Double, &controls.move_speed, &speed_lo, &speed_hi, "%.1f");
    ImGui::TextDisabled("WASD move, Space/Shift up/down,\nleft-drag rotate, wheel zoom");
    ImGui::End();
}

}  // namespace

int main(int argc, char** argv) {
    const lab::LabInfo info{LAB_NAME, LAB_DEFAULT_SCENE_DIR "/" LAB_NAME ".json", LAB_SHADER_DIR};  // scenes/<lab>.json
    return lab::run_lab(argc, argv, info, [](lab::LabApp& app, const lab::Scene& scene) {
        Camera camera = Camera::from_scene(scene.camera);
        Controls controls;
        Lighting lighting = Lighting::from_scene(scene);
        lighting.mip_view = app.options().dev.mip_view;  // headless pictures of the mip levels
        lighting.animate_lights = app.options().dev.animate_lights;  // headless: what --benchmark times
        lighting.shadow_view = app.options().dev.shadow_view;        // headless pictures of a map
        auto renderer = std::make_unique<Renderer>(app.vk(), app.target(), scene, lighting, app.shader_dir());
        lab::SceneReloader reloader(app.options().scene, scene);
        const auto rebuild = [&](const lab::Scene& fresh) {
            Lighting reloaded = Lighting::from_scene(fresh);  // replaces the panel's edits (the panel says so)
            reloaded.animate_lights = lighting.animate_lights;
            auto next = std::make_unique<Renderer>(app.vk(), app.target(), fresh, reloaded, app.shader_dir());
            app.wait_idle();  // in-flight frames may still use the old buffers
            renderer = std::move(next);
            lighting = std::move(reloaded);
        };

        lab::LabApp::Callbacks callbacks;
        callbacks.update = [&](float dt) {
            // The window draws on demand: a reload (or its error) is something new to show.
            if (app.has_window() && reloader.poll(app.key_pressed(GLFW_KEY_R), rebuild)) app.request_redraw();
            update_camera(app, camera, controls, dt);
            if (lighting.animate_lights) {  // lab 4: every light circles the Y axis, 0.5 rad/s
                animate_lights(lighting, dt);
                app.request_redraw();
            }
        };
        callbacks.ui = [&] {
            camera_panel(app, camera, controls, reloader);
            lighting_panel(lighting);
            const TranslucentLayers* layers = renderer->translucent_layers();  // lab 4: what the last frame's lists lost
            shadows_panel(lighting, app.average_frame_ms(), renderer->shadow_maps_rendered_last_frame(),
                          renderer->shadow_maps_drawn(), layers ? layers->summary() : "");
            if (textures_panel(lighting, renderer->texture_warnings(), renderer->anisotropic_auto(), app.average_frame_ms()) ||
                !renderer->shadows_match(lighting)) {  // lab 4: or other lights cast shadows, other resolutions
                // New maps / samplers / sampling mode: new images, descriptor sets and pipelines.
                auto next = std::make_unique<Renderer>(app.vk(), app.target(), reloader.scene(), lighting, app.shader_dir());
                app.wait_idle();
                renderer = std::move(next);
            }
        };
        callbacks.record = [&](const lab::Frame& frame) {
            const double aspect = double(frame.extent.width) / double(frame.extent.height);
            renderer->draw(frame, glm::mat4(camera.view()), glm::mat4(camera.projection(aspect)),
                           glm::vec3(camera.world_position()), lighting);
        };
        callbacks.background = [&] { return reloader.scene().background; };
        callbacks.before_pass = [&](const lab::Frame& frame) {  // lab 4: before the pass
            renderer->clear_translucent_layers(frame);
            const double aspect = double(frame.extent.width) / double(frame.extent.height);
            renderer->draw_shadow_maps(frame, camera.projection(aspect) * camera.view(), lighting);
        };
        app.run(callbacks);
        std::printf("%s: %d shadow map renders\n", LAB_NAME, renderer->shadow_map_renders());
        if (renderer->shadow_map_renders() > 0)
            std::printf("%s: texels per side drawn, of the resolution: %s\n", LAB_NAME, renderer->shadow_maps_drawn().c_str());
        if (renderer->shadow_map_renders() > 0)
            std::printf("%s: opaque casters' triangles drawn, of their own: %s\n", LAB_NAME, renderer->shadow_maps_triangles().c_str());
        if (TranslucentLayers* layers = renderer->translucent_layers(); layers && !app.has_window()) {
            layers->collect();  // the last frame's counts (the GPU is idle now)
            if (layers->stats().overflow_pixels > 0 || layers->stats().dropped > 0) {
                std::fflush(stdout);  // after the lines above
                std::fprintf(stderr, "%s: warning: %s\n", LAB_NAME, layers->summary().c_str());
            }
        }
    });
}
