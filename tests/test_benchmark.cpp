// The benchmark's frame accounting (common/dev/benchmark.h): how many frames the loop renders for N
// timed intervals, and a warm-up that lasts at least its frames and its milliseconds. Only the
// bookkeeping: what the figures say about a lab is bench/'s business.
#include "benchmark.h"

#include <gtest/gtest.h>

#include <chrono>

using lab::dev::Benchmark;

namespace {
// Drives `b` as the frame loop does (dev/instruments.cpp): frame i + 1 submitted, then frame i
// finished. Returns the frames rendered.
int run_loop(Benchmark& b) {
    int rendered = 0;
    while (b.wants_frame(rendered)) {
        ++rendered;
        if (rendered > 1) b.frame_finished(rendered - 2);
        if (rendered > 100000) break;  // a loop that never ends fails below
    }
    return rendered;
}
}  // namespace

TEST(Benchmark, WithoutAWarmUpTimeItSkipsThreeFramesAndTimesN) {
    Benchmark b(10, 0);
    EXPECT_EQ(run_loop(b), Benchmark::kWarmupFrames + 10 + 1);  // n + 1 finished frames for n intervals, one in flight
    EXPECT_EQ(b.warmup_frames(), Benchmark::kWarmupFrames);
    EXPECT_EQ(b.timed_frames(), 10u);
}

TEST(Benchmark, TheWarmUpLastsAtLeastItsMilliseconds) {
    Benchmark b(5, 30);
    const auto start = std::chrono::steady_clock::now();
    int index = 0;
    while (!b.frame_finished(index)) ++index;  // frames that finish at once: only the time can end it
    const double elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    EXPECT_GE(elapsed_ms, 30.0);
    EXPECT_EQ(b.warmup_frames(), index + 1);
    EXPECT_GE(b.warmup_frames(), Benchmark::kWarmupFrames);
    EXPECT_EQ(b.timed_frames(), 0u);  // the warm-up's frames are not timed
    EXPECT_TRUE(b.wants_frame(b.warmup_frames()));
    EXPECT_FALSE(b.wants_frame(b.warmup_frames() + 5 + 1));
}

TEST(Benchmark, OffRendersNothingForIt) {
    Benchmark b(0, 1000);
    EXPECT_FALSE(b.on());
    EXPECT_FALSE(b.wants_frame(0));
    EXPECT_FALSE(b.frame_finished(0));
}
