// The progress line's estimate of the time left (render/progress.h): under a time limit it never
// runs past the limit (beyond what the first pass needs), and under adaptive sampling it is a
// bound. `glint render --time-limit 3 --max-spp 4096` announced "ETA 150.0s".
#include "render/progress.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// 100 pixels up to 4096 spp, a first pass of 8.
ProgressPlan timeLimited(double seconds, bool adaptive = false) {
  ProgressPlan plan;
  plan.totalWork = 100 * 4096;
  plan.workIsBound = adaptive;
  plan.timeLimitSeconds = seconds;
  plan.firstPassWork = 100 * 8;
  return plan;
}

TEST(Progress, WithoutALimitTheEtaIsTheWorkLeftAtTheRateSoFar) {
  ProgressPlan plan;
  plan.totalWork = 1000;
  // 250 of 1000 in 2 s: 750 more at 125 per second is 6 s.
  const ProgressEstimate e = estimateProgress(plan, 250, 2.0);
  ASSERT_TRUE(e.etaSeconds);
  EXPECT_NEAR(*e.etaSeconds, 6.0, 1e-12);
  EXPECT_NEAR(e.fraction, 0.25, 1e-12);
  EXPECT_FALSE(e.limitedByTime);
  EXPECT_EQ(etaText(e), "ETA 6.0s");
}

TEST(Progress, ATimeLimitEndsTheEstimateAtTheLimit) {
  // 1 s into a 3-s limit with 16 of 4096 spp done: the work alone would take
  // (409600 − 1600) / 1600 = 255 s more; the limit leaves 2 s.
  const ProgressEstimate e = estimateProgress(timeLimited(3), 1600, 1.0);
  ASSERT_TRUE(e.etaSeconds);
  EXPECT_NEAR(*e.etaSeconds, 2.0, 1e-12);
  EXPECT_TRUE(e.limitedByTime);
  // 1 s of the 3 the render will take.
  EXPECT_NEAR(e.fraction, 1.0 / 3.0, 1e-12);
  EXPECT_EQ(etaText(e), "ETA 2.0s (time limit)");
}

TEST(Progress, TheFirstPassFinishesPastTheLimit) {
  // 4 s into a 3-s limit, the first pass (800 samples) half done at 100 samples per second: it
  // finishes whatever the limit, 4 s from now.
  const ProgressEstimate e = estimateProgress(timeLimited(3), 400, 4.0);
  ASSERT_TRUE(e.etaSeconds);
  EXPECT_NEAR(*e.etaSeconds, 4.0, 1e-12);
  EXPECT_TRUE(e.limitedByTime);
  // Past the first pass and the limit, the pass under way is the last: nothing is left.
  const ProgressEstimate after = estimateProgress(timeLimited(3), 1600, 4.0);
  EXPECT_NEAR(*after.etaSeconds, 0.0, 1e-12);
  EXPECT_NEAR(after.fraction, 1.0, 1e-12);
}

TEST(Progress, AdaptiveSamplingGivesABoundUnlessTheLimitIsNearer) {
  ProgressPlan plan;
  plan.totalWork = 1000;
  plan.workIsBound = true;
  // 6 s if every pixel takes every pass; pixels that meet the target stop sooner.
  const ProgressEstimate e = estimateProgress(plan, 250, 2.0);
  EXPECT_EQ(etaText(e), "ETA at most 6.0s");
  // With a 100-s limit the work's bound (4095 s) is the larger: the limit ends it, for certain.
  const ProgressEstimate limited = estimateProgress(timeLimited(100, true), 100, 1.0);
  EXPECT_NEAR(*limited.etaSeconds, 99.0, 1e-12);
  EXPECT_EQ(etaText(limited), "ETA 99.0s (time limit)");
}

TEST(Progress, NoEstimateBeforeAnyWork) {
  const ProgressEstimate e = estimateProgress(timeLimited(3), 0, 0.5);
  EXPECT_FALSE(e.etaSeconds);
  EXPECT_EQ(etaText(e), "ETA unknown");
  EXPECT_EQ(e.fraction, 0);
}

}  // namespace
}  // namespace glint
