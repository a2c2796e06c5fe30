#include "frame_phases.h"

#include "benchmark.h"  // ms_between

#include <cstdio>

namespace lab::dev {

// The loop's target with a clock around it: a frame starts at begin_frame(); it has its frame slot
// and image when the commands before the pass begin; end_frame() is submit and present.
class FramePhases::TimedTarget : public RenderTarget {
public:
    TimedTarget(RenderTarget& target, FramePhases& phases) : target_(target), phases_(phases) {}
    VkRenderPass render_pass() const override { return target_.render_pass(); }
    VkExtent2D extent() const override { return target_.extent(); }
    bool begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass) override {
        phases_.frame_ = {};
        phases_.frame_start_ = Clock::now();
        return target_.begin_frame(clear_linear, frame, [&](const Frame& begun) {
            phases_.frame_[Acquire] = ms_between(phases_.frame_start_, Clock::now());
            if (before_pass) before_pass(begun);
        });
    }
    void end_frame(const AfterPass& after_pass) override {
        const auto submit = Clock::now();
        target_.end_frame(after_pass);
        const auto done = Clock::now();
        phases_.frame_[SubmitPresent] = ms_between(submit, done);
        // The UI's share: the rest of the frame (its panels, overlay and copies).
        phases_.frame_[Ui] = ms_between(phases_.frame_start_, submit) - phases_.frame_[Acquire] - phases_.frame_[Record];
        for (size_t i = 0; i < kCount; ++i) phases_.ms_[i] += phases_.frame_[i];
    }
    void wait_for_previous_frame() const override { target_.wait_for_previous_frame(); }

private:
    RenderTarget& target_;
    FramePhases& phases_;
};

FramePhases::FramePhases() = default;
FramePhases::~FramePhases() = default;

RenderTarget& FramePhases::timed(RenderTarget& target) {
    target_ = std::make_unique<TimedTarget>(target, *this);
    return *target_;
}

FramePhases::LabCommands FramePhases::timed(LabCommands commands) {
    if (!commands) return commands;
    return [this, commands](const Frame& frame) {
        const auto start = Clock::now();
        commands(frame);
        frame_[Record] += ms_between(start, Clock::now());
    };
}

void FramePhases::reset(uint64_t ui_redraws) {
    ms_ = {};
    ui_redraws_at_reset_ = ui_redraws;
}

void FramePhases::print(const std::string& lab, size_t frames, uint64_t ui_redraws) const {
    if (frames == 0) return;
    const double n = double(frames);
    std::printf("breakdown lab=%s acquire_ms=%.3f ui_ms=%.3f record_ms=%.3f submit_present_ms=%.3f ui_redraws=%llu\n",
                lab.c_str(), ms_[Acquire] / n, ms_[Ui] / n, ms_[Record] / n, ms_[SubmitPresent] / n,
                static_cast<unsigned long long>(ui_redraws - ui_redraws_at_reset_));
    std::fflush(stdout);
}

}  // namespace lab::dev
