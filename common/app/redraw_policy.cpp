#include "redraw_policy.h"

namespace lab {

bool RedrawPolicy::should_draw(const Inputs& in) {
    const bool something_changed = in.event_count != seen_events_ || in.input_held || in.requested || in.continuous;
    seen_events_ = in.event_count;
    if (something_changed) frames_left_ = kSettleFrames;
    if (frames_left_ == 0) return false;
    --frames_left_;
    return true;
}

}  // namespace lab
