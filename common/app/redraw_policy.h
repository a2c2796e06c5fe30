// redraw_policy.h — render on demand: when a window frame is worth drawing.
//
// A picture that cannot have changed is not drawn again: the frame loop sleeps in
// glfwWaitEventsTimeout() until an event arrives. A frame is drawn when
//   - an event arrived (input, resize, expose, focus),
//   - a key or mouse button is held (moving, dragging: every frame changes),
//   - the lab asked for one (a scene reload, an animation),
//   - rendering is continuous (--frames, --benchmark, or the panel's checkbox),
// and then a few more frames (kSettleFrames) so that ImGui settles: a hovered button lights up
// one frame after the pointer arrives, a released click is seen one frame after the press.
#pragma once

#include <cstdint>

namespace lab {

class RedrawPolicy {
public:
    static constexpr int kSettleFrames = 3;
    // The longest sleep: the loop still wakes this often to watch the scene file (and to blink
    // the text cursor while a UI field is being edited).
    static constexpr double kWakeSeconds = 0.4;

    struct Inputs {
        uint64_t event_count = 0;  // events seen so far (Window::event_count)
        bool input_held = false;   // a key or mouse button is down
        bool requested = false;    // the lab asked for a frame (LabApp::request_redraw)
        bool continuous = false;   // draw every frame
    };

    // Called once per loop iteration, after events were processed: draw this iteration?
    bool should_draw(const Inputs& in);
    // May the loop sleep until the next event (nothing left to draw)?
    bool may_sleep() const { return frames_left_ == 0; }

private:
    uint64_t seen_events_ = 0;
    int frames_left_ = kSettleFrames;  // the first frames of a window are always drawn
};

}  // namespace lab
