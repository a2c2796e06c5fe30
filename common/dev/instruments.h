// instruments.h — the tooling the frame loop calls at a few named points: the --benchmark timing
// and its report, the window's time breakdown, the status file, memory given back when a window
// goes idle, and the injected failure. Each is off unless its flag asked for it (--benchmark,
// --dev-…: app/dev_options.h). Nothing here changes a picture.
#pragma once

#include "benchmark.h"
#include "status_file.h"

#include <cstdint>
#include <memory>
#include <string>

namespace lab::dev {

struct InstrumentSettings {
    std::string lab;            // names the report lines
    int benchmark_frames = 0;   // --benchmark N: N timed frames (0: off)
    std::string status_file;    // --dev-status-file PATH (empty: off)
    int fail_after_submit = 0;  // --dev-fail-after-submit N (0: off)
};

class Instruments {
public:
    explicit Instruments(InstrumentSettings settings);

    bool benchmarking() const { return benchmark_.on(); }
    // Frames a benchmark renders: the warm-up, then one more than the intervals it times.
    int benchmark_frames() const { return benchmark_.frames_to_render(); }
    FramePhases& phases() { return phases_; }

    // ---- The loop's named points.
    // A frame was submitted. The test hook throws here after the Nth, as a lost surface or device
    // would (tests/test_vulkan_correctness.cpp: the run must still end validation-clean).
    void frame_submitted();
    // A window frame was drawn at `width` × `height` (the status file).
    void window_frame_drawn(uint32_t width, uint32_t height);
    // A window went idle after drawing: its frames are done; memory goes back to the system.
    void window_went_idle();
    // Frame `index` (from 0) finished on the GPU (benchmark timing). `ui_redraws`: the UI's count.
    void frame_finished(int index, uint64_t ui_redraws);
    // The benchmark's report lines, after the last frame (a window adds its breakdown); false
    // when no frame was timed (a window closed during the warm-up).
    bool report(uint32_t width, uint32_t height, bool window, uint64_t ui_redraws) const;

private:
    InstrumentSettings settings_;
    Benchmark benchmark_;
    FramePhases phases_;
    std::unique_ptr<StatusFile> status_;
    int submitted_ = 0;
};

}  // namespace lab::dev
