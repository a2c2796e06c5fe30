// lab_app.cpp — the frame loop (lab_app.h): window or headless, input, UI, the PNG. The entry
// point around it, with its exit codes, is run_lab.cpp.
#include "lab_app.h"

#include "headless_target.h"
#include "redraw_policy.h"
#include "window_target.h"

#include "instruments.h"  // dev layer: benchmark, status file, test hooks

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

namespace lab {

namespace {
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The passes the loop itself names (a lab names its own, pass_timer.h).
constexpr const char* kMainPass = "main pass";
constexpr const char* kUiPass = "UI";

std::string format_ms(float ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", ms);
    return text;
}

Frame with_timer(Frame frame, PassTimer* timer) {
    frame.timer = timer;
    return frame;
}

// The device's largest image side for a colour attachment. The command line allows up to 65536;
// a larger image than the device can make is bad input like any other (one line, exit code 2).
void check_image_size(const VulkanContext& vk, const Options& options) {
    const VkPhysicalDeviceLimits& limits = vk.properties().limits;
    const uint32_t max_width = std::min(limits.maxImageDimension2D, limits.maxFramebufferWidth);
    const uint32_t max_height = std::min(limits.maxImageDimension2D, limits.maxFramebufferHeight);
    const auto check = [&](const char* option, uint32_t value, uint32_t allowed) {
        if (value > allowed)
            throw CliError(std::string(option) + " " + std::to_string(value) + ": the device allows at most " +
                           std::to_string(allowed) + " (" + vk.properties().deviceName + ")");
    };
    check("--width", options.width, max_width);
    check("--height", options.height, max_height);
}
}  // namespace

LabApp::LabApp(const LabInfo& info, const Options& options, int* validation_messages)
    : info_(info),
      options_(options),
      shader_dir_(options.dev.shader_dir.empty() ? info.shader_dir : options.dev.shader_dir) {
    ContextOptions context;
    context.validate = options.validate;
    context.message_count = validation_messages;
    context.validation_probe = options.dev.validation_probe;
    context.no_blit = options.dev.no_blit;
    context.without_features = options.dev.without_features;
    context.minimum_limits = options.dev.minimum_limits;
    if (!options.headless) {
        window_ = std::make_unique<Window>(info.name, options.width, options.height);
        context.window = window_->handle();
    }
    vk_ = std::make_unique<VulkanContext>(context);
    check_image_size(*vk_, options);
    if (window_) {
        window_->show();  // created hidden: bad input never flashes a window
        auto target = std::make_unique<WindowTarget>(*vk_, *window_);
        ui_ = std::make_unique<ImGuiLayer>(*vk_, window_->handle(), target->render_pass(), target->color_format(),
                                           target->accepts_copies());
        target_ = std::move(target);
    } else {
        auto target = std::make_unique<HeadlessTarget>(*vk_, VkExtent2D{options.width, options.height});
        headless_ = target.get();
        target_ = std::move(target);
    }
    dev::InstrumentSettings instruments;
    instruments.lab = info.name;
    instruments.benchmark_frames = options.benchmark;
    instruments.warmup_ms = options.dev.warmup_ms;
    instruments.window = window_ != nullptr;
    instruments.status_file = window_ ? options.dev.status_file : "";
    instruments.fail_after_submit = options.dev.fail_after_submit;
    dev_ = std::make_unique<dev::Instruments>(*vk_, instruments);
}

LabApp::~LabApp() {
    if (vk_) vkDeviceWaitIdle(vk_->device());
    ui_.reset();
    target_.reset();
    dev_.reset();  // its query pools
    vk_.reset();
    window_.reset();
}

void LabApp::wait_idle() const { VK_CHECK(vkDeviceWaitIdle(vk_->device())); }

bool LabApp::key_down(int glfw_key) const {
    if (!window_ || (ui_ && ui_->wants_keyboard())) return false;
    return glfwGetKey(window_->handle(), glfw_key) == GLFW_PRESS;
}

bool LabApp::key_pressed(int glfw_key) {
    // From the key events, not the key's state: a tap whose press and release arrive between two
    // frames, or a second tap before a frame saw the first one's release, still counts.
    if (!window_) return false;
    const bool pressed = window_->take_key_press(glfw_key);
    return pressed && !(ui_ && ui_->wants_keyboard());  // typed into a UI field: not a command
}

void LabApp::poll_input() {
    // The cursor as the window's callbacks left it: asking GLFW (glfwGetCursorPos) would be a
    // round trip to the X server every frame.
    const glm::dvec2 cursor = window_->input().cursor;
    const bool ui_has_mouse = ui_ && ui_->wants_mouse();
    mouse_.delta = have_cursor_ && !ui_has_mouse ? glm::vec2(cursor - last_cursor_) : glm::vec2(0.0f);
    mouse_.left_down = !ui_has_mouse && window_->input().mouse_down[GLFW_MOUSE_BUTTON_LEFT];
    const float scroll = window_->take_scroll();
    mouse_.scroll = ui_has_mouse ? 0.0f : scroll;
    last_cursor_ = cursor;
    have_cursor_ = true;
}

void LabApp::run(const Callbacks& callbacks) {
    // The lab's renderer is a local of its body, destroyed as soon as run() is left. Whichever
    // way run() is left (the last frame, or an exception after a submit: a lost surface or
    // device, a failed pipeline), the GPU must be done with every submitted frame first, or
    // unwinding destroys pipelines, buffers and memory the GPU is still using.
    try {
        if (window_)
            run_window(callbacks);
        else
            run_headless(callbacks);
    } catch (...) {
        // The original error is the one to report; a failing wait here (a lost device) has
        // nothing left to wait for.
        vkDeviceWaitIdle(vk_->device());
        throw;
    }
}

void LabApp::run_window(const Callbacks& lab_callbacks) {
    // --frames and --benchmark draw every frame and stop after a count. Otherwise the window
    // draws on demand (redraw_policy.h) and sleeps while nothing changes.
    const bool measured = options_.frames > 0 || dev_->benchmarking();
    RenderTarget& target = dev_->measured(*target_);  // a window benchmark times the frame's phases
    Callbacks cb = lab_callbacks;
    cb.before_pass = dev_->measured(cb.before_pass);
    cb.record = dev_->measured(cb.record);

    RedrawPolicy policy;
    const auto start = Clock::now();
    auto last_update = start, last_ui = start;
    int drawn = 0, drawn_when_idle = 0;
    while (!window_->should_close()) {
        // 1. Events: wait for one when there is nothing to draw, else just take what came.
        const bool sleep = !measured && !continuous_rendering_ && policy.may_sleep();
        if (sleep && drawn > drawn_when_idle) {  // going idle after drawing: finish, give memory back
            wait_idle();
            dev_->window_went_idle();
            drawn_when_idle = drawn;
        }
        if (sleep)
            window_->wait_events(RedrawPolicy::kWakeSeconds);
        else
            glfwPollEvents();
        const auto woke = Clock::now();
        poll_input();

        // 2. Update. Held keys move by real time; after a sleep nothing was held (or we would not
        // have slept), so the time asleep is not movement time.
        if (sleep) last_update = woke;
        cb.update(std::chrono::duration<float>(woke - last_update).count());
        last_update = woke;

        // 3. Draw, if anything changed: UI, record, submit, present.
        RedrawPolicy::Inputs in;
        in.event_count = window_->event_count();
        in.input_held = window_->input_held();
        in.requested = std::exchange(redraw_requested_, false) || (ui_->wants_text_input() && sleep);
        in.continuous = measured || continuous_rendering_;
        if (!policy.should_draw(in)) continue;
        if (!draw_window_frame(target, cb, std::chrono::duration<float>(woke - last_ui).count())) continue;
        last_ui = woke;
        if (drawn > 0) show_frame_time(woke);  // the first frame compiles the shaders: not a frame time
        dev_->frame_drawn(target, target.extent(), ui_->redraw_count());
        ++drawn;
        if (dev_->benchmarking() ? !dev_->benchmark_wants_frame(drawn) : measured && drawn >= options_.frames)
            break;  // --frames N: screenshots, tests; --benchmark N: its warm-up and N intervals
    }
    wait_idle();
    if (dev_->benchmarking() && dev_->report(target_->extent(), ui_->redraw_count())) return;
    const double seconds = seconds_since(start);
    std::printf("%s: %d frames in %.1f s (%.1f ms/frame average)\n", info_.name.c_str(), drawn, seconds,
                drawn ? 1000.0 * seconds / drawn : 0.0);
}

// The frame's cost from waking up to presenting (not the time asleep before it), for the panel.
void LabApp::show_frame_time(Clock::time_point woke) {
    const float work_ms = float(1000.0 * seconds_since(woke));
    recent_frames_.add(work_ms);
    // Also while no GPU time is shown: a frame's times arrive a frame or two later (after its
    // fence), and a window drawn on demand may draw only those few frames.
    if (shown_frame_ms_ == 0.0f || shown_gpu_ms_.empty() || woke - shown_at_ >= std::chrono::milliseconds(500)) {
        shown_frame_ms_ = recent_frames_.median();
        shown_gpu_ms_.clear();
        for (const dev::PassTime& pass : dev_->gpu_passes().recent_medians()) shown_gpu_ms_.emplace_back(pass.name, float(pass.ms));
        shown_at_ = woke;
    }
}

bool LabApp::draw_window_frame(RenderTarget& target, const Callbacks& cb, float ui_dt) {
    // The UI is built first: nothing of the frame is recorded yet, so a panel may replace what
    // the lab draws with (a new renderer). Then the lab's own commands outside the pass (lab 4's
    // shadow maps), then the overlay, redrawn if the UI changed; its translucent edges are blended
    // over the lab's picture inside the pass, its opaque panels copied in after it (imgui_renderer.h).
    // Each pass's GPU time (gpu_timer.h): the lab's own passes, the main pass, the UI's three parts.
    dev::GpuPassTimer& gpu = dev_->gpu_passes();
    PassTimer* timer = gpu.frame_timer();
    std::optional<TimedPass> main_pass;  // from before the render pass begins to the lab's last draw
    const BeforePass before_pass = [&](const Frame& begun) {
        gpu.begin_frame(begun.cmd, begun.slot);
        ui_->new_frame(*window_, ui_dt);
        cb.ui();
        if (cb.before_pass) cb.before_pass(with_timer(begun, timer));
        {
            const TimedPass timed(timer, begun.cmd, kUiPass);
            ui_->prepare(begun.cmd, begun.slot, begun.extent);
        }
        main_pass.emplace(timer, begun.cmd, kMainPass);
    };
    Frame frame;
    if (!target.begin_frame(cb.background(), frame, before_pass)) return false;  // minimized, or a new swapchain
    frame.timer = timer;
    cb.record(frame);
    main_pass.reset();
    {
        const TimedPass timed(timer, frame.cmd, kUiPass);
        ui_->render(frame.cmd);
    }
    target.end_frame([&](VkCommandBuffer cmd, VkImage image) {
        const TimedPass timed(timer, cmd, kUiPass);
        ui_->render_after_pass(cmd, image);
    });
    return true;
}

void LabApp::frame_stats_ui() {
    const bool continuous = continuous_rendering_ || options_.frames > 0 || options_.benchmark > 0;
    if (continuous)
        ImGui::Text("%.2f ms/frame (%.0f fps)", shown_frame_ms_, 1000.0 / std::max(shown_frame_ms_, 1e-3f));
    else
        ImGui::Text("%.2f ms/frame, drawn on demand", shown_frame_ms_);
    gpu_times_ui();
    ImGui::Checkbox("continuous rendering", &continuous_rendering_);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Draw frames all the time, not only when something changes\n(uses a CPU core while idle)");
}

// Where the GPU's time goes: each pass the frame named, and their sum (medians of the recent frames).
void LabApp::gpu_times_ui() {
    if (!dev_->gpu_passes().supported()) {
        ImGui::TextDisabled("GPU time: this device has no timestamps");
        return;
    }
    float sum = 0.0f;
    for (const auto& [name, ms] : shown_gpu_ms_) sum += ms;
    // A fold of its own, closed at first so the panels keep their places (the label changes with
    // the sum; "###" keeps its id, and its state). Open it to see each pass.
    const std::string label =
        (shown_gpu_ms_.empty() ? std::string("GPU: no frame timed yet") : "GPU " + format_ms(sum) + " ms/frame") + "###gpu passes";
    const bool open = ImGui::TreeNodeEx(label.c_str(), ImGuiTreeNodeFlags_None);
    if (ImGui::IsItemHovered())  // what a pass's time is (gpu_timer.h): the passes never overlap
        ImGui::SetTooltip("Each pass: from when all GPU work before it is done to when it is done too\n"
                          "(the time it adds to the frame; the sum leaves out work between passes)");
    // The panel was sized to its first frame, before any pass was timed: refit its height when
    // the lines below change, or they would push the panel's own widgets out of sight.
    const size_t lines = open ? shown_gpu_ms_.size() : 0;
    if (lines != gpu_lines_shown_) ImGui::SetWindowSize(ImVec2(ImGui::GetWindowWidth(), 0.0f));
    gpu_lines_shown_ = lines;
    if (!open) return;
    if (shown_gpu_ms_.empty()) ImGui::TextDisabled("times arrive after a frame's fence: tick continuous rendering");
    for (const auto& [name, ms] : shown_gpu_ms_) ImGui::TextDisabled("%s %.2f ms", name.c_str(), ms);
    ImGui::TreePop();
}

void LabApp::run_headless(const Callbacks& cb) {
    // Headless time advances at a fixed rate, so the output is deterministic.
    const int frames = std::max(1, options_.frames);
    dev::GpuPassTimer& gpu = dev_->gpu_passes();
    const auto start = Clock::now();
    for (int i = 0; dev_->benchmarking() ? dev_->benchmark_wants_frame(i) : i < frames; ++i) {
        cb.update(1.0f / 60.0f);
        Frame frame;
        std::optional<TimedPass> main_pass;  // from before the render pass begins to the lab's last draw
        target_->begin_frame(cb.background(), frame, [&](const Frame& begun) {
            gpu.begin_frame(begun.cmd, begun.slot);
            if (cb.before_pass) cb.before_pass(with_timer(begun, gpu.frame_timer()));
            main_pass.emplace(gpu.frame_timer(), begun.cmd, kMainPass);
        });
        frame.timer = gpu.frame_timer();
        cb.record(frame);
        main_pass.reset();
        target_->end_frame();
        dev_->frame_drawn(*target_, target_->extent(), 0);
    }
    wait_idle();
    if (dev_->benchmarking()) {
        dev_->report(target_->extent(), 0);
        if (options_.out.empty()) return;
    } else {
        std::printf("%s: rendered %d frame%s at %ux%u in %.1f ms\n", info_.name.c_str(), frames, frames == 1 ? "" : "s",
                    options_.width, options_.height, 1000.0 * seconds_since(start));
    }
    const std::string out = options_.out.empty() ? info_.name + ".png" : options_.out;
    write_png(out, headless_->read_pixels());
    std::printf("%s: wrote %s\n", info_.name.c_str(), std::filesystem::absolute(out).string().c_str());
    std::fflush(stdout);
}

}  // namespace lab
