#include "lab_app.h"

#include "headless_target.h"
#include "redraw_policy.h"
#include "window_target.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <utility>

namespace lab {

namespace {
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Percentile of a sample (nearest-rank on the sorted values).
double percentile(std::vector<double> values, double p) {
    std::sort(values.begin(), values.end());
    const size_t rank = size_t(std::max(0.0, std::ceil(p / 100.0 * double(values.size())) - 1.0));
    return values[std::min(rank, values.size() - 1)];
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

// Gives the memory freed since the last call back to the system (glibc: malloc_trim). Called when
// the window goes idle after drawing. Why: a rebuilt renderer (a scene reload) makes llvmpipe
// compile its shaders at the first draw, and LLVM's many small temporary blocks come from glibc's
// heaps (below the mmap threshold set in run_lab); once freed they stay resident while a few live
// blocks between them keep the heap from shrinking, and lavapipe's large images are carved from
// that free space too. Resident memory then climbed although nothing leaked (lab 4, 4 minutes of
// bench/soak.sh: glibc's heaps 149 -> 227 MB, their free part 43 -> 150 MB, the blocks in use
// not growing; at rest 396 -> 445 MB, +12 %). malloc_trim gives back every whole free page of
// every heap, so what stays resident is what is in use (the same run: +1.6 %, 292 -> 298 MB). It
// takes 2 ms (at most 30 ms seen), spent while nobody waits for a frame.
void give_back_free_memory() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}
}  // namespace

LabApp::LabApp(const LabInfo& info, const Options& options, int* validation_messages)
    : info_(info), options_(options) {
    ContextOptions context;
    context.validate = options.validate;
    context.message_count = validation_messages;
    if (!options.headless) {
        window_ = std::make_unique<Window>(info.name, options.width, options.height);
        context.window = window_->handle();
    }
    vk_ = std::make_unique<VulkanContext>(context);
    check_image_size(*vk_, options);
    if (window_) {
        window_->show();  // created hidden: bad input never flashes a window
        target_ = std::make_unique<WindowTarget>(*vk_, *window_);
        const auto& window_target = static_cast<const WindowTarget&>(*target_);
        ui_ = std::make_unique<ImGuiLayer>(*vk_, window_->handle(), window_target.render_pass(),
                                           window_target.color_format(), window_target.accepts_copies());
        status_ = StatusFile::from_environment();
    } else {
        auto target = std::make_unique<HeadlessTarget>(*vk_, VkExtent2D{options.width, options.height});
        headless_ = target.get();
        target_ = std::move(target);
    }
    // Test-only: fail right after the Nth frame is submitted, as a lost surface or device would
    // (tests/test_vulkan_correctness.cpp checks that the run still ends validation-clean).
    if (const char* n = std::getenv("LAB_TEST_FAIL_AFTER_SUBMIT"); n && *n) fail_after_submit_ = std::atoi(n);
}

LabApp::~LabApp() {
    if (vk_) vkDeviceWaitIdle(vk_->device());
    ui_.reset();
    target_.reset();
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

void LabApp::frame_submitted() {
    if (++submitted_ == fail_after_submit_)
        throw VulkanError("LAB_TEST_FAIL_AFTER_SUBMIT=" + std::to_string(fail_after_submit_) +
                          ": injected failure right after submitting frame " + std::to_string(submitted_));
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

void LabApp::run_window(const Callbacks& cb) {
    // --frames and --benchmark measure: every frame is drawn. Otherwise the window draws on
    // demand (redraw_policy.h) and sleeps while nothing changes.
    const bool measured = options_.frames > 0 || options_.benchmark > 0;
    const int warmup = options_.benchmark > 0 ? 3 : 0;  // as headless: pipeline compilation, caches
    const int to_draw = options_.benchmark > 0 ? warmup + options_.benchmark + 1 : options_.frames;
    std::vector<double> frame_ms;

    RedrawPolicy policy;
    const auto start = Clock::now();
    auto last_update = start, last_ui = start, last_done = start;
    int frame_count = 0, drawn_at_trim = 0;
    while (!window_->should_close()) {
        // Sleep until an event (or the periodic wake) when there is nothing to draw.
        const bool slept = !measured && !continuous_rendering_ && policy.may_sleep();
        if (slept && frame_count > drawn_at_trim) {  // idle after drawing: the last frame done, memory back
            wait_idle();
            give_back_free_memory();
            drawn_at_trim = frame_count;
            if (status_) status_->went_idle();
        }
        if (slept)
            window_->wait_events(RedrawPolicy::kWakeSeconds);
        else
            glfwPollEvents();
        const auto woke = Clock::now();
        poll_input();
        // Held keys move by real time. After a sleep nothing was held (or we would not have
        // slept): the time asleep is not movement time.
        if (slept) last_update = woke;
        const float dt = std::chrono::duration<float>(woke - last_update).count();
        last_update = woke;
        cb.update(dt);

        RedrawPolicy::Inputs in;
        in.event_count = window_->event_count();
        in.input_held = window_->input_held();
        in.requested = std::exchange(redraw_requested_, false) || (ui_ && ui_->wants_text_input() && slept);
        in.continuous = measured || continuous_rendering_;
        if (!policy.should_draw(in)) continue;

        const float ui_dt = std::chrono::duration<float>(woke - last_ui).count();
        if (!draw_window_frame(cb, ui_dt)) continue;
        last_ui = woke;
        ++frame_count;
        // The frame's cost, from waking up to presenting (not the time spent asleep before it).
        const float work_ms = float(ms_since(woke));
        average_frame_ms_ = average_frame_ms_ == 0.0f ? work_ms : 0.95f * average_frame_ms_ + 0.05f * work_ms;
        if (shown_frame_ms_ == 0.0f || woke - shown_at_ >= std::chrono::milliseconds(500)) {
            shown_frame_ms_ = average_frame_ms_;
            shown_at_ = woke;
        }

        if (options_.benchmark > 0 && frame_count > 1) {
            // As headless: the interval between two consecutive frames finishing on the GPU.
            static_cast<WindowTarget&>(*target_).wait_for_slot((last_slot_ + 1) % RenderTarget::kFramesInFlight);
            const auto done = Clock::now();
            if (frame_count - 1 > warmup) frame_ms.push_back(std::chrono::duration<double, std::milli>(done - last_done).count());
            if (frame_count - 1 == warmup) {  // the breakdown leaves out the warm-up frames too
                phase_ms_ = {};
                ui_redraws_at_warmup_ = ui_->redraw_count();
            }
            last_done = done;
        }
        if (measured && frame_count >= to_draw) break;  // --frames N: screenshots, tests
    }
    wait_idle();
    if (options_.benchmark > 0 && !frame_ms.empty()) {
        print_benchmark("window", frame_ms);
        const double n = double(frame_ms.size());
        std::printf("breakdown lab=%s acquire_ms=%.3f ui_ms=%.3f record_ms=%.3f submit_present_ms=%.3f "
                    "ui_redraws=%llu\n",
                    info_.name.c_str(), phase_ms_[0] / n, phase_ms_[1] / n, phase_ms_[2] / n, phase_ms_[3] / n,
                    static_cast<unsigned long long>(ui_->redraw_count() - ui_redraws_at_warmup_));
        std::fflush(stdout);
        return;
    }
    const double seconds = ms_since(start) / 1000.0;
    std::printf("%s: %d frames in %.1f s (%.1f ms/frame average)\n", info_.name.c_str(), frame_count, seconds,
                frame_count ? 1000.0 * seconds / frame_count : 0.0);
}

bool LabApp::draw_window_frame(const Callbacks& cb, float ui_dt) {
    // Where a window frame's time goes (printed by --benchmark N --window): waiting for a frame
    // slot and a swapchain image; building and recording the UI; recording the lab's draws;
    // submitting and presenting (with a CPU driver such as lavapipe, presenting also waits for
    // the frame to be rendered and copies it to the window system).
    auto mark = Clock::now();
    const auto phase = [&](size_t i) {
        const auto now = Clock::now();
        phase_ms_[i] += std::chrono::duration<double, std::milli>(now - mark).count();
        mark = now;
    };
    // The UI is built first: nothing of the frame is recorded yet, so a panel may replace what
    // the lab draws with (a new renderer). Then the lab's own commands outside the pass (lab 4's
    // shadow maps), then the overlay, redrawn if the UI changed; its translucent edges are blended
    // over the lab's picture inside the pass, its opaque panels copied in after it (imgui_renderer.h).
    const BeforePass before_pass = [&](const Frame& begun) {
        phase(0);
        ui_->new_frame(*window_, ui_dt);
        cb.ui();
        phase(1);
        if (cb.before_pass) cb.before_pass(begun);
        phase(2);
        ui_->prepare(begun.cmd, begun.slot, begun.extent);
        phase(1);
    };
    Frame frame;
    if (!target_->begin_frame(cb.background(), frame, before_pass)) return false;
    cb.record(frame);
    phase(2);
    ui_->render(frame.cmd);
    phase(1);
    static_cast<WindowTarget&>(*target_).end_frame(
        [&](VkCommandBuffer cmd, VkImage image) { ui_->render_after_pass(cmd, image); });
    phase(3);
    frame_submitted();
    last_slot_ = frame.slot;
    if (status_) status_->frame_drawn(frame.extent.width, frame.extent.height);
    return true;
}

void LabApp::frame_stats_ui() {
    const bool continuous = continuous_rendering_ || options_.frames > 0 || options_.benchmark > 0;
    if (continuous)
        ImGui::Text("%.2f ms/frame (%.0f fps)", shown_frame_ms_, 1000.0 / std::max(shown_frame_ms_, 1e-3f));
    else
        ImGui::Text("%.2f ms/frame, drawn on demand", shown_frame_ms_);
    ImGui::Checkbox("continuous rendering", &continuous_rendering_);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Draw frames all the time, not only when something changes\n(uses a CPU core while idle)");
}

void LabApp::print_benchmark(const char* mode, const std::vector<double>& frame_ms) const {
    double mean = 0.0;
    for (double v : frame_ms) mean += v / double(frame_ms.size());
    // One machine-readable line (key=value pairs) for scripts and bench/.
    std::printf("benchmark lab=%s width=%u height=%u frames=%zu min_ms=%.3f median_ms=%.3f p95_ms=%.3f mean_ms=%.3f%s%s\n",
                info_.name.c_str(), target_->extent().width, target_->extent().height, frame_ms.size(),
                *std::min_element(frame_ms.begin(), frame_ms.end()), percentile(frame_ms, 50.0),
                percentile(frame_ms, 95.0), mean, mode ? " target=" : "", mode ? mode : "");
    std::fflush(stdout);
}

void LabApp::run_headless(const Callbacks& cb) {
    const bool benchmark = options_.benchmark > 0;
    const int warmup = benchmark ? 3 : 0;  // first frames pay for pipeline compilation and caches
    const int frames = benchmark ? options_.benchmark : std::max(1, options_.frames);
    std::vector<double> frame_ms;
    frame_ms.reserve(size_t(frames));

    // A benchmark frame time is the interval between two consecutive frames
    // *finishing* on the GPU, with two frames in flight as in a real loop —
    // the same throughput figure a windowed program's frame rate gives.
    const auto start = Clock::now();
    auto last_done = start;
    const int total = benchmark ? warmup + frames + 1 : frames;  // +1: n intervals need n + 1 frames
    for (int i = 0; i < total; ++i) {
        cb.update(1.0f / 60.0f);  // headless time advances at a fixed rate: deterministic output
        Frame frame;
        target_->begin_frame(cb.background(), frame, cb.before_pass);
        cb.record(frame);
        target_->end_frame();
        frame_submitted();
        if (benchmark && i > 0) {
            headless_->wait_for_frame(i - 1);  // the previous frame is done: one interval
            const auto done = Clock::now();
            if (i > warmup) frame_ms.push_back(std::chrono::duration<double, std::milli>(done - last_done).count());
            last_done = done;
        }
    }
    wait_idle();
    const double total_ms = ms_since(start);

    if (benchmark) {
        print_benchmark(nullptr, frame_ms);
    } else {
        std::printf("%s: rendered %d frame%s at %ux%u in %.1f ms\n", info_.name.c_str(), frames, frames == 1 ? "" : "s",
                    options_.width, options_.height, total_ms);
    }
    if (!benchmark || !options_.out.empty()) {
        const std::string out = options_.out.empty() ? info_.name + ".png" : options_.out;
        write_png(out, headless_->read_pixels());
        std::printf("%s: wrote %s\n", info_.name.c_str(), std::filesystem::absolute(out).string().c_str());
    }
    std::fflush(stdout);
}

int run_lab(int argc, char** argv, const LabInfo& info,
            const std::function<void(LabApp& app, const Scene& scene)>& body) {
    const std::string name = info.name;
    int validation_messages = 0;
#ifdef __GLIBC__
    // Big blocks (images, swapchain and staging memory: lavapipe mallocs them) straight from the
    // OS and back to it when freed. By default glibc raises this threshold after the first big
    // free and serves later big blocks from the heap, where a window resized and reloaded a few
    // hundred times leaves holes: resident memory then creeps up by megabytes though nothing
    // leaks (bench/soak.sh measured +2.7 % in 4 minutes; with a fixed threshold: flat).
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
    try {
        // The scene folder can be moved: LAB_SCENE_DIR overrides the compiled-in one.
        std::string default_scene = info.default_scene;
        if (const char* dir = std::getenv("LAB_SCENE_DIR"); dir && *dir)
            default_scene = std::string(dir) + "/" + std::filesystem::path(default_scene).filename().string();

        Options options = parse_command_line(argc, argv, default_scene);
        if (options.help) {
            std::printf("%s", usage(name).c_str());
            return 0;
        }
        if (!options.out.empty()) {  // fail before rendering, not after
            const std::filesystem::path folder = std::filesystem::absolute(options.out).parent_path();
            if (!std::filesystem::is_directory(folder))
                throw CliError("--out " + options.out + ": folder " + folder.string() + " does not exist");
        }
        const Scene scene = load_scene(options.scene);
        {
            LabApp app(info, options, &validation_messages);
            body(app, scene);
        }  // everything Vulkan is destroyed here, so leaks are reported before we count
        if (validation_messages > 0) {
            std::fprintf(stderr, "%s: error: %d validation message%s (see above)\n", name.c_str(), validation_messages,
                         validation_messages == 1 ? "" : "s");
            return 1;
        }
        return 0;
    } catch (const CliError& e) {
        const std::string message = e.what();
        const bool has_hint = message.find("--help") != std::string::npos || message.find("did you mean") != std::string::npos;
        std::fprintf(stderr, "%s: error: %s%s\n", name.c_str(), message.c_str(), has_hint ? "" : " (try --help)");
        return 2;
    } catch (const SceneError& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 2;
    } catch (const VulkanError& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 1;
    } catch (const std::runtime_error& e) {  // bad input found while loading (meshes, images)
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 1;
    }
}

}  // namespace lab
