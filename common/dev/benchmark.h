// benchmark.h — what `--benchmark N` measures and prints (the dev layer: no lab code calls it).
//
// A frame time is the interval between two consecutive frames *finishing* on the GPU, with two
// frames in flight as in a real loop: the throughput a program's frame rate shows. The warm-up is
// left out: at least kWarmupFrames (pipeline compilation, caches) and at least `warmup_ms` of
// frames (--dev-warmup-ms, default 1000). A GPU that has been idle may run at a low clock and raise
// it only after some time under load, and a short benchmark from a cold start would then time the
// clock's climb, not the program (the H200 lent here was at its top clock at once, lavapipe has no
// such climb: docs/performance.md, "How the figures are measured"). The report is one machine-readable
// line of key=value pairs for scripts and bench/:
//   benchmark lab=… width=… height=… frames=… min_ms=… median_ms=… p95_ms=… mean_ms=… [target=window]
//             device=… device_type=cpu|integrated|discrete|virtual|other
// A time means little without the device that made it: the fastest settings on lavapipe (a CPU) are
// not those of a GPU. The device's name has its spaces as '_', so every value is one word.
#pragma once

#include <vulkan/vulkan.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace lab::dev {

// Milliseconds from `a` to `b` (the dev layer's clock arithmetic).
inline double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// The report's `device=… device_type=…` fields (without a leading space).
std::string device_fields(const VkPhysicalDeviceProperties& device);

class Benchmark {
public:
    static constexpr int kWarmupFrames = 3;

    // `frames` timed intervals (0: no benchmark; every method is then a no-op) after the warm-up.
    Benchmark(int frames, int warmup_ms);
    bool on() const { return frames_ > 0; }
    // Whether the loop must render another frame: the warm-up is not over, or fewer than `frames`
    // intervals are timed. `rendered`: frames submitted so far (one more than have finished).
    bool wants_frame(int rendered) const;
    // Frame number `index` (from 0) has finished on the GPU. True when this ended the warm-up.
    bool frame_finished(int index);
    size_t timed_frames() const { return frame_ms_.size(); }
    int warmup_frames() const { return warmup_frames_; }  // the frames the warm-up took
    // The report line on stdout (`mode`: nullptr, or "window"; `device`: what ran it).
    void print(const std::string& lab, uint32_t width, uint32_t height, const char* mode,
               const VkPhysicalDeviceProperties& device) const;

private:
    using Clock = std::chrono::steady_clock;
    int frames_;
    double warmup_ms_;
    int warmup_frames_ = -1;  // -1: warming up
    Clock::time_point first_done_, last_done_;
    std::vector<double> frame_ms_;
};

}  // namespace lab::dev
