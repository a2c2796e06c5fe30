// The GPU timer's arithmetic (common/dev/gpu_timer.h): timestamp ticks to milliseconds with the
// device's period, across a counter's wrap-around, and a pass's name as a benchmark key. The
// timer on a device is tested by tests/gpu_passes.py.
#include "gpu_timer.h"

#include <gtest/gtest.h>

#include <cstdint>

using lab::dev::pass_key;
using lab::dev::ticks_to_ms;

TEST(GpuTimer, TicksTimesThePeriodAreNanoseconds) {
    // lavapipe: 1 ns per tick, 64 valid bits. 3,500,000 ticks = 3.5 ms.
    EXPECT_DOUBLE_EQ(ticks_to_ms(1000, 3'501'000, 64, 1.0), 3.5);
    // A 52.08 ns period: 1000 ticks = 52,080 ns = 0.05208 ms.
    EXPECT_NEAR(ticks_to_ms(5000, 6000, 64, 52.08), 0.05208, 1e-12);
    EXPECT_DOUBLE_EQ(ticks_to_ms(42, 42, 36, 10.0), 0.0);
}

TEST(GpuTimer, A36BitCounterThatWrappedStillGivesTheTime) {
    // begin 100 ticks before 2^36, end 50 ticks after it wrapped to 0: 150 ticks of 10 ns.
    const uint64_t wrap = uint64_t(1) << 36;
    EXPECT_NEAR(ticks_to_ms(wrap - 100, 50, 36, 10.0), 0.0015, 1e-15);
    // The same 150 ticks without a wrap.
    EXPECT_NEAR(ticks_to_ms(1000, 1150, 36, 10.0), 0.0015, 1e-15);
}

TEST(GpuTimer, ThirtyTwoAndSixtyFourBitCountersWrapToo) {
    EXPECT_DOUBLE_EQ(ticks_to_ms(0xFFFF'FFF0u, 0x10u, 32, 1e6), 32.0);  // 32 ticks of 1 ms
    EXPECT_DOUBLE_EQ(ticks_to_ms(UINT64_MAX - 9, 10, 64, 1e6), 20.0);  // 20 ticks of 1 ms
}

TEST(GpuTimer, PassNamesBecomeBenchmarkKeys) {
    EXPECT_EQ(pass_key("main pass"), "main_pass");
    EXPECT_EQ(pass_key("UI"), "ui");
    EXPECT_EQ(pass_key("map: spot 1"), "map_spot_1");
    EXPECT_EQ(pass_key("translucent map: point 12"), "translucent_map_point_12");
    EXPECT_EQ(pass_key(" -odd--name- "), "odd_name");
}
