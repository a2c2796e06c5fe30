// frame_phases.h — where a window frame's time goes (printed after `--benchmark N --window`):
// waiting for a frame slot and a swapchain image; building and recording the UI; recording the
// lab's draws; submitting and presenting (with a CPU driver such as lavapipe, presenting also waits
// for the frame to be rendered and copies it to the window system).
//
// Measured from outside the frame loop: the loop draws through a timed stand-in for its target and
// timed copies of the lab's two recording callbacks; the UI's share is what is left of the frame.
#pragma once

#include "render_target.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace lab::dev {

class FramePhases {
public:
    using LabCommands = std::function<void(const Frame&)>;

    FramePhases();
    ~FramePhases();

    // `target`, its frames timed (the object lives as long as this one).
    RenderTarget& timed(RenderTarget& target);
    // `commands` (a lab's record or before_pass), timed as the lab's recording.
    LabCommands timed(LabCommands commands);

    void reset(uint64_t ui_redraws);  // leaves out what came before (the warm-up)
    void print(const std::string& lab, size_t frames, uint64_t ui_redraws) const;

private:
    class TimedTarget;
    enum Phase { Acquire, Ui, Record, SubmitPresent, kCount };
    using Clock = std::chrono::steady_clock;

    std::unique_ptr<TimedTarget> target_;
    std::array<double, kCount> ms_{};     // summed over the frames since reset()
    std::array<double, kCount> frame_{};  // the frame being drawn
    Clock::time_point frame_start_{};
    uint64_t ui_redraws_at_reset_ = 0;
};

}  // namespace lab::dev
