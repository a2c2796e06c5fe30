#include "benchmark.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace lab::dev {
namespace {

// Percentile of a sample (nearest-rank on the sorted values).
double percentile(std::vector<double> values, double p) {
    std::sort(values.begin(), values.end());
    const size_t rank = size_t(std::max(0.0, std::ceil(p / 100.0 * double(values.size())) - 1.0));
    return values[std::min(rank, values.size() - 1)];
}

const char* type_name(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    default: return "other";
    }
}

}  // namespace

std::string device_fields(const VkPhysicalDeviceProperties& device) {
    std::string name = device.deviceName;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    if (name.empty()) name = "unnamed";
    for (char& c : name)
        if (c == ' ' || c == '\t' || c == '=') c = '_';  // one word, so `key=value` parsers keep it whole
    return "device=" + name + " device_type=" + type_name(device.deviceType);
}

Benchmark::Benchmark(int frames, int warmup_ms)
    : frames_(std::max(frames, 0)), warmup_ms_(std::max(warmup_ms, 0)), last_done_(Clock::now()) {
    frame_ms_.reserve(size_t(frames_));
}

bool Benchmark::wants_frame(int rendered) const {
    if (!on()) return false;
    // n intervals need n + 1 finished frames after the warm-up; one frame is always still in flight.
    return warmup_frames_ < 0 || rendered < warmup_frames_ + frames_ + 1;
}

bool Benchmark::frame_finished(int index) {
    if (!on()) return false;
    const auto done = Clock::now();
    if (index == 0) first_done_ = done;
    const bool warm = warmup_frames_ >= 0;
    if (warm) frame_ms_.push_back(ms_between(last_done_, done));
    last_done_ = done;
    if (warm || index < kWarmupFrames - 1 || ms_between(first_done_, done) < warmup_ms_) return false;
    warmup_frames_ = index + 1;
    return true;
}

void Benchmark::print(const std::string& lab, uint32_t width, uint32_t height, const char* mode,
                      const VkPhysicalDeviceProperties& device) const {
    double mean = 0.0;
    for (double v : frame_ms_) mean += v / double(frame_ms_.size());
    std::printf("benchmark lab=%s width=%u height=%u frames=%zu min_ms=%.3f median_ms=%.3f p95_ms=%.3f mean_ms=%.3f%s%s %s\n",
                lab.c_str(), width, height, frame_ms_.size(), *std::min_element(frame_ms_.begin(), frame_ms_.end()),
                percentile(frame_ms_, 50.0), percentile(frame_ms_, 95.0), mean, mode ? " target=" : "",
                mode ? mode : "", device_fields(device).c_str());
    std::fflush(stdout);
}

}  // namespace lab::dev
