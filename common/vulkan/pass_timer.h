// pass_timer.h — how a lab names its passes for the panel's GPU times. A lab only marks where a
// pass's commands begin and end, with one line:
//   const lab::TimedPass timed(frame.timer, cmd, "main pass");
// The dev layer (dev/gpu_timer.h) writes GPU timestamps there; the panel and --benchmark show
// the times. With no timer (null, or a device without timestamps) nothing is recorded.
#pragma once

#include <vulkan/vulkan.h>

#include <string_view>

namespace lab {

class PassTimer {
public:
    virtual ~PassTimer() = default;
    // Marks the start of pass `name` in `cmd`; the handle for end(), or -1 when it is not timed.
    virtual int begin(VkCommandBuffer cmd, std::string_view name) = 0;
    virtual void end(VkCommandBuffer cmd, int pass) = 0;
};

// Times the commands recorded while it lives as pass `name`. Passes do not nest; passes of the
// same name in one frame add up (a cube map's six faces).
class TimedPass {
public:
    TimedPass(PassTimer* timer, VkCommandBuffer cmd, std::string_view name)
        : timer_(timer), cmd_(cmd), pass_(timer ? timer->begin(cmd, name) : -1) {}
    ~TimedPass() {
        if (pass_ >= 0) timer_->end(cmd_, pass_);
    }
    TimedPass(const TimedPass&) = delete;
    TimedPass& operator=(const TimedPass&) = delete;

private:
    PassTimer* timer_;
    VkCommandBuffer cmd_;
    int pass_;
};

}  // namespace lab
