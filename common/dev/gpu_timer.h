// gpu_timer.h — the GPU time of each named pass (pass_timer.h), from timestamp queries: what the
// panel shows under the frame time and `--benchmark` prints as its `gpu_passes` line.
//
// One query pool per frame in flight. A frame's commands start by resetting its slot's pool; each
// pass writes a timestamp where it begins and one where it ends, both at BOTTOM_OF_PIPE: each is
// latched once all the commands before it have completed, so a pass's time runs from "all earlier
// work done" to "it is done too" — the time it adds to the frame — and the passes' times never
// overlap, on any device (their sum is at most the frame's span). The
// results of a slot's frame are read only when the slot comes round again, after its fence has
// signalled: reading never waits for the GPU. A device or queue without timestamps says so once;
// then, or when the timer is off, nothing is recorded at all.
#pragma once

#include "pass_timer.h"
#include "render_target.h"
#include "vk_context.h"

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace lab::dev {

// Milliseconds between two timestamps of a counter with `valid_bits` bits (the queue family's
// timestampValidBits) ticking every `period_ns` nanoseconds (timestampPeriod). The difference is
// taken modulo 2^valid_bits, so a counter that wrapped between the two still gives the time.
double ticks_to_ms(uint64_t begin, uint64_t end, uint32_t valid_bits, double period_ns);

struct PassTime {
    std::string name;
    double ms = 0.0;
};

// One frame's passes (same-named ones added up, in the order they first began) and its span: from
// the first pass's start to the last one's end.
struct FrameGpuTimes {
    uint64_t frame = 0;  // the frame's number, from 0
    std::vector<PassTime> passes;
    double span_ms = 0.0;
};

class GpuPassTimer : public PassTimer {
public:
    static constexpr uint32_t kMaxPasses = 64;     // per frame; later ones are not timed
    static constexpr size_t kRecentFrames = 30;    // what the panel's medians are taken over

    // `on`: record timestamps (when the device has them). `keep_all`: keep every frame's times
    // (a benchmark's report), not only the recent ones.
    GpuPassTimer(const VulkanContext& vk, bool on, bool keep_all);
    ~GpuPassTimer() override;
    GpuPassTimer(const GpuPassTimer&) = delete;
    GpuPassTimer& operator=(const GpuPassTimer&) = delete;

    bool supported() const { return valid_bits_ > 0; }
    bool on() const { return on_ && supported(); }
    // The timer frames hand to the lab: this one when on, else null (nothing recorded).
    PassTimer* frame_timer() { return on() ? this : nullptr; }

    // At the start of frame slot `slot`'s commands, outside any render pass, once the slot's fence
    // has signalled: takes the results of the slot's previous frame, resets its queries.
    void begin_frame(VkCommandBuffer cmd, uint32_t slot);
    int begin(VkCommandBuffer cmd, std::string_view name) override;
    void end(VkCommandBuffer cmd, int pass) override;
    // Once the device is idle: takes the results of the frames not read yet.
    void collect();

    // The panel's numbers: each pass of the last frame read, as the median over the recent frames
    // that had it.
    std::vector<PassTime> recent_medians() const;
    // The benchmark's line: each pass's, the passes' sum's and the span's median over the `count`
    // frames from number `first` (the frames the benchmark timed); false when there is none.
    bool print(const std::string& lab, uint64_t first, uint64_t count) const;

private:
    struct Slot {
        Handle<VkQueryPool> pool;
        std::vector<std::string> names;  // the passes begun in the slot's frame, in order
        uint64_t frame = 0;
        bool pending = false;  // written and not read yet
    };
    void read(Slot& slot);

    const VulkanContext& vk_;
    bool on_;
    bool keep_all_;
    uint32_t valid_bits_ = 0;
    double period_ns_ = 0.0;
    std::array<Slot, RenderTarget::kFramesInFlight> slots_;
    Slot* current_ = nullptr;  // the frame being recorded
    uint64_t frames_ = 0;
    bool said_too_many_ = false;
    std::deque<FrameGpuTimes> done_;  // frames read, oldest first
};

// "map: spot 1" -> "map_spot_1": a pass's name as a key of the benchmark line.
std::string pass_key(std::string_view name);

}  // namespace lab::dev
