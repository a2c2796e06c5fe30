// lab_app.h — the frame loop every lab shares: window or headless, input, UI, PNG.
//
// A lab's body (run_lab.h starts it) creates its renderer, fills LabApp::Callbacks and calls
// app.run(frame).
#pragma once

#include "cli.h"
#include "imgui_layer.h"
#include "recent_frames.h"
#include "render_target.h"
#include "scene.h"
#include "vk_context.h"

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lab {

namespace dev {
class Instruments;  // benchmark, status file, test hooks: the dev layer, behind the loop
}
class Window;
class HeadlessTarget;

struct LabInfo {
    std::string name;           // "lab1_camera": window title, default PNG name
    std::string default_scene;  // absolute path of the lab's scene in scenes/
    std::string shader_dir;     // absolute path of the lab's compiled shaders (build/shaders/<lab>)
};

// What the mouse did since the last frame (zero while the pointer is over a UI panel).
struct MouseInput {
    glm::vec2 delta{0.0f};  // pixels moved
    float scroll = 0.0f;     // wheel steps
    bool left_down = false;
};

class LabApp {
public:
    // What the lab does each frame, in this order.
    struct Callbacks {
        std::function<void(float dt_seconds)> update;  // input and animation
        std::function<void()> ui;                      // ImGui panels (window only), before anything is recorded
        std::function<glm::vec3()> background;         // clear colour (linear RGB)
        BeforePass before_pass;                        // optional: commands before the pass (lab 4's shadow maps)
        std::function<void(const Frame&)> record;      // draw commands inside the render pass
    };

    LabApp(const LabInfo& info, const Options& options, int* validation_messages);
    ~LabApp();

    const Options& options() const { return options_; }
    const VulkanContext& vk() const { return *vk_; }
    RenderTarget& target() { return *target_; }
    bool has_window() const { return window_ != nullptr; }
    // The lab's compiled shaders (--dev-shader-dir replaces the folder built in).
    const std::string& shader_dir() const { return shader_dir_; }

    // Keyboard (false when headless or while an ImGui text field has focus).
    bool key_down(int glfw_key) const;
    bool key_pressed(int glfw_key);  // pressed since the last call (each press counts once)
    const MouseInput& mouse() const { return mouse_; }
    // The recent frame time as the panels show it: refreshed twice a second, not every frame (a
    // number that changes every frame is unreadable, and it would make the UI overlay be redrawn
    // every frame, see imgui_renderer.h).
    float average_frame_ms() const { return shown_frame_ms_; }
    // The frame time line, the GPU time of each pass and the "continuous rendering" checkbox, for
    // the lab's panel.
    void frame_stats_ui();
    // Something the picture depends on changed outside the input (a scene reload, an animation):
    // draw a frame even though no event arrived (a window draws only on demand, see redraw_policy.h).
    void request_redraw() { redraw_requested_ = true; }
    // Waits until the GPU is idle (before destroying resources in-flight frames may still use).
    void wait_idle() const;

    // Renders until the window closes or --frames/--benchmark are done; headless writes the PNG.
    void run(const Callbacks& callbacks);

private:
    void run_window(const Callbacks& callbacks);
    void run_headless(const Callbacks& callbacks);
    bool draw_window_frame(RenderTarget& target, const Callbacks& callbacks, float ui_dt);  // false: no image
    void poll_input();
    void show_frame_time(std::chrono::steady_clock::time_point woke);
    void gpu_times_ui();

    LabInfo info_;
    Options options_;
    std::string shader_dir_;
    std::unique_ptr<Window> window_;
    std::unique_ptr<VulkanContext> vk_;
    std::unique_ptr<RenderTarget> target_;
    HeadlessTarget* headless_ = nullptr;  // == target_ when headless (it reads the picture back)
    std::unique_ptr<ImGuiLayer> ui_;
    std::unique_ptr<dev::Instruments> dev_;
    MouseInput mouse_;
    glm::dvec2 last_cursor_{0.0};
    bool have_cursor_ = false;
    RecentFrames recent_frames_;   // the work of the last frames drawn
    float shown_frame_ms_ = 0.0f;  // their median when last shown
    std::vector<std::pair<std::string, float>> shown_gpu_ms_;  // each pass's GPU time, shown with it
    size_t gpu_lines_shown_ = 0;  // the panel's pass lines last frame (a change refits the panel)
    std::chrono::steady_clock::time_point shown_at_{};
    bool continuous_rendering_ = false;  // the panel's checkbox: draw every frame, even when idle
    bool redraw_requested_ = false;
};

}  // namespace lab
