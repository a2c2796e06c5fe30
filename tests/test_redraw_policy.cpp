// The render-on-demand rule (common/app/redraw_policy.h): which loop iterations draw a frame; and the
// frame time the panels show (common/app/recent_frames.h).
#include "redraw_policy.h"
#include "recent_frames.h"

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

// --- the frame time the panels show (common/app/recent_frames.h) ---------------------------

TEST(RecentFrames, MedianOfTheLastFramesForgetsOneSlowFrame) {
    lab::RecentFrames recent;
    EXPECT_EQ(recent.median(), 0.0f);  // nothing drawn yet
    recent.add(8000.0f);               // a frame that compiled shaders
    EXPECT_EQ(recent.median(), 8000.0f);
    recent.add(5.0f);
    recent.add(6.0f);
    EXPECT_EQ(recent.median(), 6.0f);  // {5, 6, 8000}: the slow frame no longer shows
    for (int i = 0; i < 20; ++i) recent.add(4.0f);
    EXPECT_EQ(recent.median(), 4.0f);  // only the last kFrames count
}

TEST(RecentFrames, FollowsARealChangeWithinHalfTheWindow) {
    lab::RecentFrames recent;
    for (size_t i = 0; i < lab::RecentFrames::kFrames; ++i) recent.add(10.0f);
    for (size_t i = 0; i < lab::RecentFrames::kFrames / 2; ++i) recent.add(30.0f);
    EXPECT_EQ(recent.median(), 10.0f);  // 7 of 15 slower: not yet
    recent.add(30.0f);
    EXPECT_EQ(recent.median(), 30.0f);  // 8 of 15: the median moves
}
