// recent_frames.h — the frame time a panel shows: the median of the last frames' work.
//
// A mean (or a running average) lets one slow frame linger: the first frame compiles every shader
// (seconds on llvmpipe) and a running average seeded with it showed "8493 ms/frame" long after the
// frames had become fast. The median of the last kFrames ignores such a frame once a few normal
// ones have followed it, and still follows a real change of cost within half the window.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace lab {

class RecentFrames {
public:
    static constexpr size_t kFrames = 15;

    void add(float ms) {
        ms_[next_] = ms;
        next_ = (next_ + 1) % kFrames;
        count_ = std::min(count_ + 1, kFrames);
    }
    // The median of the frames seen (up to the last kFrames); 0 before the first.
    float median() const {
        if (count_ == 0) return 0.0f;
        std::array<float, kFrames> sorted = ms_;
        std::nth_element(sorted.begin(), sorted.begin() + count_ / 2, sorted.begin() + count_);
        return sorted[count_ / 2];
    }

private:
    std::array<float, kFrames> ms_{};
    size_t next_ = 0, count_ = 0;
};

}  // namespace lab
