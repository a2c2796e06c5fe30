#include "instruments.h"

#include "process_memory.h"
#include "vk_check.h"

namespace lab::dev {

Instruments::Instruments(const VulkanContext& vk, InstrumentSettings settings)
    : settings_(std::move(settings)),
      device_(vk.properties()),
      benchmark_(settings_.benchmark_frames, settings_.warmup_ms),
      gpu_passes_(vk, settings_.window || benchmark_.on(), benchmark_.on()) {
    if (!settings_.status_file.empty()) status_ = std::make_unique<StatusFile>(settings_.status_file);
}

RenderTarget& Instruments::measured(RenderTarget& target) {
    return benchmarking() && settings_.window ? phases_.timed(target) : target;
}

FramePhases::LabCommands Instruments::measured(FramePhases::LabCommands lab_commands) {
    return benchmarking() && settings_.window ? phases_.timed(std::move(lab_commands)) : lab_commands;
}

void Instruments::frame_drawn(RenderTarget& target, VkExtent2D extent, uint64_t ui_redraws) {
    if (++drawn_ == settings_.fail_after_submit)
        throw VulkanError("--dev-fail-after-submit " + std::to_string(settings_.fail_after_submit) +
                          ": injected failure right after submitting frame " + std::to_string(drawn_));
    if (status_) status_->frame_drawn(extent.width, extent.height);
    if (benchmarking() && drawn_ > 1) {  // the frame before this one is done: one interval
        target.wait_for_previous_frame();
        if (benchmark_.frame_finished(drawn_ - 2)) phases_.reset(ui_redraws);  // the breakdown skips the warm-up too
    }
}

void Instruments::window_went_idle() {
    // The device is idle: the last frames' GPU times are there (a window drawn on demand may draw
    // no further frame that would read them), so the panel shows them at its next frame.
    gpu_passes_.collect();
    give_back_free_memory();
    if (status_) status_->went_idle();
}

bool Instruments::report(VkExtent2D extent, uint64_t ui_redraws) {
    if (benchmark_.timed_frames() == 0) return false;
    benchmark_.print(settings_.lab, extent.width, extent.height, settings_.window ? "window" : nullptr, device_);
    gpu_passes_.collect();  // the last frames' results
    gpu_passes_.print(settings_.lab, uint64_t(benchmark_.warmup_frames()), benchmark_.timed_frames());
    if (settings_.window) phases_.print(settings_.lab, benchmark_.timed_frames(), ui_redraws);
    return true;
}

}  // namespace lab::dev
