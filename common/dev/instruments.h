// instruments.h — the tooling the frame loop calls at a few named points: the --benchmark timing
// and its report, the window's time breakdown, the status file, memory given back when a window
// goes idle, and the injected failure. Each is off unless its flag asked for it (--benchmark,
// --dev-…: app/dev_options.h). Nothing here changes a picture.
#pragma once

#include "benchmark.h"
#include "frame_phases.h"
#include "render_target.h"
#include "status_file.h"

#include <cstdint>
#include <memory>
#include <string>

namespace lab::dev {

struct InstrumentSettings {
    std::string lab;            // names the report lines
    int benchmark_frames = 0;   // --benchmark N: N timed frames (0: off)
    bool window = false;        // a window (a benchmark also says where a frame's time goes)
    std::string status_file;    // --dev-status-file PATH (empty: off)
    int fail_after_submit = 0;  // --dev-fail-after-submit N (0: off)
};

class Instruments {
public:
    explicit Instruments(InstrumentSettings settings);

    bool benchmarking() const { return benchmark_.on(); }
    // Frames a benchmark renders: the warm-up, then one more than the intervals it times.
    int benchmark_frames() const { return benchmark_.frames_to_render(); }
    // What the loop draws through: `target` and the lab's commands as they are, or timed
    // (frame_phases.h) when a window benchmark asks where the time goes.
    RenderTarget& measured(RenderTarget& target);
    FramePhases::LabCommands measured(FramePhases::LabCommands lab_commands);

    // ---- The loop's named points.
    // A frame was submitted (and presented). The test hook throws here after the Nth, as a lost
    // surface or device would (tests/test_vulkan_correctness.cpp: the run must still end
    // validation-clean); a window's status file gets its line; a benchmark waits for the frame
    // before it to finish on the GPU and times it. `ui_redraws`: the UI overlay's count (0 headless).
    void frame_drawn(RenderTarget& target, VkExtent2D extent, uint64_t ui_redraws);
    // A window went idle after drawing: its frames are done; memory goes back to the system.
    void window_went_idle();
    // The benchmark's report lines, after the last frame (a window adds its breakdown); false
    // when no frame was timed (a window closed during the warm-up).
    bool report(VkExtent2D extent, uint64_t ui_redraws) const;

private:
    InstrumentSettings settings_;
    Benchmark benchmark_;
    FramePhases phases_;
    std::unique_ptr<StatusFile> status_;
    int drawn_ = 0;
};

}  // namespace lab::dev
