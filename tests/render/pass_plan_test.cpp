// The pass schedule and the per-pixel estimates, on values worked out by hand.
#include "render/pass_plan.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace glint {
namespace {

TEST(PassPlan, PlainRenderDoublesFromTwoToTheSpp) {
  // 16 spp: passes end at 2, 4, 8, 16; 12 spp: 2, 4, 8, then the last pass to 12.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, {}).ends, (std::vector<int>{2, 4, 8, 16}));
  EXPECT_EQ(PassPlan::make(12, SamplerKind::Stratified, {}).ends, (std::vector<int>{2, 4, 8, 12}));
  // One sample: one pass of it.
  EXPECT_EQ(PassPlan::make(1, SamplerKind::Stratified, {}).ends, (std::vector<int>{1}));
  // Without a target or a time limit the sampler is the scene's.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, {}).sampler, SamplerKind::Stratified);
}

TEST(PassPlan, AdaptiveRenderStartsAtMinSppAndUsesAProgressiveSampler) {
  SamplingRequest r;
  r.target.rmse = 0.01;
  r.maxSpp = 256;
  const PassPlan plan = PassPlan::make(16, SamplerKind::Stratified, r);
  // --min-spp defaults to min(16, max): 16, 32, ..., 256.
  EXPECT_EQ(plan.ends, (std::vector<int>{16, 32, 64, 128, 256}));
  EXPECT_EQ(plan.sampler, SamplerKind::Sobol);
  // A random sampler is progressive already and stays.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Random, r).sampler, SamplerKind::Random);
  // A time limit alone also leaves the final spp open.
  SamplingRequest timed;
  timed.timeLimitSeconds = 5;
  EXPECT_EQ(PassPlan::make(64, SamplerKind::Regular, timed).sampler, SamplerKind::Sobol);
}

TEST(PassPlan, ContradictoryBoundsAreRefused) {
  SamplingRequest r;
  r.minSpp = 64;
  r.maxSpp = 32;
  EXPECT_THROW(PassPlan::make(16, SamplerKind::Stratified, r), UsageError);
  SamplingRequest one;
  one.target.relmse = 0.001;
  one.minSpp = 1;  // no estimate can be made from one sample
  EXPECT_THROW(PassPlan::make(16, SamplerKind::Stratified, one), UsageError);
}

// A pixel with half 0 = {1, 3} and half 1 = {2, 6} in every channel.
PixelEstimate twoHalves() {
  PixelEstimate p;
  for (float v : {1.f, 3.f}) p.half[0].add({v, v, v}, 1);
  for (float v : {2.f, 6.f}) p.half[1].add({v, v, v}, 1);
  return p;
}

TEST(PixelEstimate, MeanAndBothVarianceEstimates) {
  const PixelEstimate p = twoHalves();
  double mean[4], v[3], s[3];
  p.mean(mean);
  EXPECT_DOUBLE_EQ(mean[0], 3.0);  // (1 + 3 + 2 + 6) / 4
  EXPECT_DOUBLE_EQ(mean[3], 1.0);
  // Halves' means 2 and 4, n0 = n1 = 2: (2·2/16)·(2 − 4)² = 1.
  ASSERT_TRUE(p.varianceOfMean(v));
  EXPECT_DOUBLE_EQ(v[0], 1.0);
  // Pooled: deviations from 3 are −2, 0, −1, 3: Σ = 14, s² = 14/3, s²/n = 14/12.
  ASSERT_TRUE(p.conservativeVarianceOfMean(s));
  EXPECT_DOUBLE_EQ(s[1], 14.0 / 12.0);
}

TEST(PixelEstimate, OneSampleHasNoEstimate) {
  PixelEstimate p;
  p.half[0].add({1, 1, 1}, 1);
  double v[3];
  EXPECT_FALSE(p.varianceOfMean(v));
  EXPECT_FALSE(p.conservativeVarianceOfMean(v));
  // A pixel without an estimate never meets a target (it keeps taking samples).
  ErrorTarget t;
  t.rmse = 1e9;
  EXPECT_FALSE(t.metBy(p));
}

TEST(ErrorTarget, RmseAndRelmseOnTheConservativeEstimate) {
  const PixelEstimate p = twoHalves();  // s²/n = 14/12 per channel, mean 3
  ErrorTarget t;
  t.rmse = std::sqrt(14.0 / 12.0) * 1.001;
  EXPECT_TRUE(t.metBy(p));
  t.rmse = std::sqrt(14.0 / 12.0) * 0.999;
  EXPECT_FALSE(t.metBy(p));
  // relMSE: (14/12) / (9 + 0.01) = 0.12948...
  ErrorTarget rel;
  rel.relmse = 0.1295;
  EXPECT_TRUE(rel.metBy(p));
  rel.relmse = 0.1294;
  EXPECT_FALSE(rel.metBy(p));
}

TEST(FrameError, AveragesPixelsLikeCompareAndIsAbsentForRegularGrids) {
  const std::vector<PixelEstimate> pixels = {twoHalves(), twoHalves()};
  const FrameError e = estimateFrameError(pixels, SamplerKind::Stratified);
  ASSERT_TRUE(e.rmse && e.relmse);
  EXPECT_DOUBLE_EQ(*e.rmse, 1.0);                 // every channel's variance is 1
  EXPECT_DOUBLE_EQ(*e.relmse, 1.0 / (9 + 0.01));  // 1 / (mean² + ε)
  EXPECT_FALSE(estimateFrameError(pixels, SamplerKind::Regular).rmse);
}

}  // namespace
}  // namespace glint
