// The render-on-demand rule (common/app/redraw_policy.h): which loop iterations draw a frame.
#include "redraw_policy.h"

#include <gtest/gtest.h>

namespace {
using lab::RedrawPolicy;

// Runs `n` iterations with the same inputs; returns how many drew.
int drawn(RedrawPolicy& policy, const RedrawPolicy::Inputs& in, int n) {
    int count = 0;
    for (int i = 0; i < n; ++i) count += policy.should_draw(in) ? 1 : 0;
    return count;
}
}  // namespace

TEST(RedrawPolicy, NewWindowDrawsSettleFramesThenSleeps) {
    RedrawPolicy policy;
    EXPECT_FALSE(policy.may_sleep());
    EXPECT_EQ(drawn(policy, {}, 100), RedrawPolicy::kSettleFrames);
    EXPECT_TRUE(policy.may_sleep());
}

TEST(RedrawPolicy, AnEventWakesItForTheSettleFrames) {
    RedrawPolicy policy;
    drawn(policy, {}, 10);
    RedrawPolicy::Inputs in;
    in.event_count = 1;  // one pointer motion
    EXPECT_TRUE(policy.should_draw(in));
    EXPECT_EQ(1 + drawn(policy, in, 100), RedrawPolicy::kSettleFrames);  // same count: no new event
    EXPECT_TRUE(policy.may_sleep());
}

TEST(RedrawPolicy, HeldInputDrawsEveryIteration) {
    RedrawPolicy policy;
    drawn(policy, {}, 10);
    RedrawPolicy::Inputs held;
    held.event_count = 1;
    held.input_held = true;
    EXPECT_EQ(drawn(policy, held, 500), 500);
    EXPECT_FALSE(policy.may_sleep());
    RedrawPolicy::Inputs released;
    released.event_count = 2;  // the release is an event
    EXPECT_EQ(drawn(policy, released, 100), RedrawPolicy::kSettleFrames);
}

TEST(RedrawPolicy, ContinuousDrawsEveryIterationAndSettlesWhenTurnedOff) {
    RedrawPolicy policy;
    RedrawPolicy::Inputs continuous;
    continuous.continuous = true;
    EXPECT_EQ(drawn(policy, continuous, 1000), 1000);
    // The last continuous frame was the first of the settling frames.
    EXPECT_EQ(drawn(policy, {}, 100), RedrawPolicy::kSettleFrames - 1);
    EXPECT_TRUE(policy.may_sleep());
}

TEST(RedrawPolicy, ARequestDrawsWithoutAnEvent) {
    RedrawPolicy policy;
    drawn(policy, {}, 10);
    RedrawPolicy::Inputs request;
    request.requested = true;  // a scene reload
    EXPECT_TRUE(policy.should_draw(request));
    EXPECT_FALSE(policy.may_sleep());
    EXPECT_EQ(1 + drawn(policy, {}, 100), RedrawPolicy::kSettleFrames);
}
