#include "instruments.h"

#include "process_memory.h"
#include "vk_check.h"

namespace lab::dev {

Instruments::Instruments(InstrumentSettings settings)
    : settings_(std::move(settings)), benchmark_(settings_.benchmark_frames) {
    if (!settings_.status_file.empty()) status_ = std::make_unique<StatusFile>(settings_.status_file);
}

void Instruments::frame_submitted() {
    if (++submitted_ == settings_.fail_after_submit)
        throw VulkanError("--dev-fail-after-submit " + std::to_string(settings_.fail_after_submit) +
                          ": injected failure right after submitting frame " + std::to_string(submitted_));
}

void Instruments::window_frame_drawn(uint32_t width, uint32_t height) {
    if (status_) status_->frame_drawn(width, height);
}

void Instruments::window_went_idle() {
    give_back_free_memory();
    if (status_) status_->went_idle();
}

void Instruments::frame_finished(int index, uint64_t ui_redraws) {
    if (benchmark_.frame_finished(index)) phases_.reset(ui_redraws);  // the breakdown skips the warm-up too
}

bool Instruments::report(uint32_t width, uint32_t height, bool window, uint64_t ui_redraws) const {
    if (benchmark_.timed_frames() == 0) return false;
    benchmark_.print(settings_.lab, width, height, window ? "window" : nullptr);
    if (window) phases_.print(settings_.lab, benchmark_.timed_frames(), ui_redraws);
    return true;
}

}  // namespace lab::dev
