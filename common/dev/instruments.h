// instruments.h — the tooling the frame loop calls at a few named points: the --benchmark timing
// and its report, the window's time breakdown, the status file, memory given back when a window
// goes idle, and the injected failure. Each is off unless its flag asked for it (--benchmark,
// --dev-…: app/dev_options.h), but the GPU time per pass: on in a window (the panel shows it) and
// in a benchmark (its gpu_passes line). Nothing here changes a picture.
#pragma once

#include "benchmark.h"
#include "frame_phases.h"
#include "gpu_timer.h"
#include "render_target.h"
#include "status_file.h"

#include <cstdint>
#include <memory>
#include <string>

namespace lab::dev {

struct InstrumentSettings {
    std::string lab;            // names the report lines
    int benchmark_frames = 0;   // --benchmark N: N timed frames (0: off)
    int warmup_ms = 0;          // --dev-warmup-ms N: the benchmark's least warm-up (its default: dev_options.h)
    bool window = false;        // a window (a benchmark also says where a frame's time goes)
    std::string status_file;    // --dev-status-file PATH (empty: off)
    int fail_after_submit = 0;  // --dev-fail-after-submit N (0: off)
};

class Instruments {
public:
    Instruments(const VulkanContext& vk, InstrumentSettings settings);

    bool benchmarking() const { return benchmark_.on(); }
    // Whether a benchmark must render another frame (`rendered`: the frames submitted so far):
    // its warm-up, then one more frame than the intervals it times.
    bool benchmark_wants_frame(int rendered) const { return benchmark_.wants_frame(rendered); }
    // What the loop draws through: `target` and the lab's commands as they are, or timed
    // (frame_phases.h) when a window benchmark asks where the time goes.
    RenderTarget& measured(RenderTarget& target);
    FramePhases::LabCommands measured(FramePhases::LabCommands lab_commands);
    // The GPU time of each pass (gpu_timer.h): on in a window and in a benchmark.
    GpuPassTimer& gpu_passes() { return gpu_passes_; }

    // ---- The loop's named points.
    // A frame was submitted (and presented). The test hook throws here after the Nth, as a lost
    // surface or device would (tests/test_vulkan_correctness.cpp: the run must still end
    // validation-clean); a window's status file gets its line; a benchmark waits for the frame
    // before it to finish on the GPU and times it. `ui_redraws`: the UI overlay's count (0 headless).
    void frame_drawn(RenderTarget& target, VkExtent2D extent, uint64_t ui_redraws);
    // A window went idle after drawing: its frames are done; memory goes back to the system.
    void window_went_idle();
    // The benchmark's report lines, after the last frame (the GPU's passes; a window adds its
    // breakdown); false when no frame was timed (a window closed during the warm-up). The device
    // must be idle.
    bool report(VkExtent2D extent, uint64_t ui_redraws);

private:
    InstrumentSettings settings_;
    VkPhysicalDeviceProperties device_;  // names the device in the benchmark's line
    Benchmark benchmark_;
    FramePhases phases_;
    GpuPassTimer gpu_passes_;
    std::unique_ptr<StatusFile> status_;
    int drawn_ = 0;
};

}  // namespace lab::dev
