// The pass schedule and the per-pixel estimates, on values worked out by hand.
#include "render/pass_plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "render/tile_scheduler.h"

namespace glint {
namespace {

TEST(PassPlan, PlainRenderDoublesFromEightToTheSpp) {
  // 64 spp: passes end at 8, 16, 32, 64; 24 spp: 8, 16, then the last pass to 24.
  EXPECT_EQ(PassPlan::make(64, SamplerKind::Stratified, {}).ends,
            (std::vector<int>{8, 16, 32, 64}));
  EXPECT_EQ(PassPlan::make(24, SamplerKind::Stratified, {}).ends, (std::vector<int>{8, 16, 24}));
  // Fewer than 8 samples: one pass of them.
  EXPECT_EQ(PassPlan::make(5, SamplerKind::Stratified, {}).ends, (std::vector<int>{5}));
  EXPECT_EQ(PassPlan::make(1, SamplerKind::Stratified, {}).ends, (std::vector<int>{1}));
  // Without a target or a time limit the sampler is the scene's.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, {}).sampler, SamplerKind::Stratified);
}

TEST(PassPlan, APlainRenderStartsAtMinSppWhenGivenAndKeepsItsSampler) {
  // --min-spp on a plain render is its first pass: equal to the spp, the frame is one pass.
  SamplingRequest r;
  r.minSpp = 16;
  const PassPlan one = PassPlan::make(16, SamplerKind::Stratified, r);
  EXPECT_EQ(one.ends, (std::vector<int>{16}));
  r.minSpp = 2;
  const PassPlan four = PassPlan::make(16, SamplerKind::Stratified, r);
  EXPECT_EQ(four.ends, (std::vector<int>{2, 4, 8, 16}));
  // Every pixel still takes the spp: the scene's own sampler, its sets laid out for the spp,
  // and the textures filtered for it, as with the default passes from 8.
  for (const PassPlan& plan : {one, four}) {
    EXPECT_EQ(plan.sampler, SamplerKind::Stratified);
    EXPECT_EQ(plan.maxSpp, 16);
    EXPECT_EQ(plan.footprintSpp(), 16);
    EXPECT_FALSE(plan.adaptive());
  }
}

TEST(PassPlan, AdaptiveRenderStartsAtMinSppAndUsesAProgressiveSampler) {
  SamplingRequest r;
  r.target.rmse = 0.01;
  r.maxSpp = 256;
  const PassPlan plan = PassPlan::make(16, SamplerKind::Stratified, r);
  // --min-spp defaults to min(8, max): 8, 16, ..., 256.
  EXPECT_EQ(plan.ends, (std::vector<int>{8, 16, 32, 64, 128, 256}));
  r.maxSpp = 4;  // a first pass of the most a pixel may take
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, r).ends, (std::vector<int>{4}));
  EXPECT_EQ(plan.sampler, SamplerKind::Sobol);
  // A random sampler is progressive already and stays.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Random, r).sampler, SamplerKind::Random);
  // A time limit alone also leaves the final spp open.
  SamplingRequest timed;
  timed.timeLimitSeconds = 5;
  EXPECT_EQ(PassPlan::make(64, SamplerKind::Regular, timed).sampler, SamplerKind::Sobol);
}

TEST(PassPlan, TexturesAreFilteredForTheTotalOnlyWhereItIsFixed) {
  // A stratified render of 16 samples shares each pixel's footprint among its 16; a render that
  // may stop or be continued at any spp filters every sample for the most there can be, 64 or
  // more (integrator/footprint.h), whatever its spp.
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, {}).footprintSpp(), 16);
  SamplingRequest resumable;
  resumable.progressive = true;
  for (const int spp : {4, 16, 1024}) {
    EXPECT_EQ(PassPlan::make(spp, SamplerKind::Stratified, resumable).footprintSpp(),
              kFinestFootprintSpp);
    EXPECT_EQ(PassPlan::make(spp, SamplerKind::Sobol, {}).footprintSpp(), kFinestFootprintSpp);
  }
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
  // Without a target or a time limit every pixel takes the spp: a --max-spp of 8 or 32 would
  // render another count than the 16 the frame's metadata names; 16 itself says nothing new.
  for (const int most : {8, 32}) {
    SamplingRequest plain;
    plain.maxSpp = most;
    EXPECT_THROW(PassPlan::make(16, SamplerKind::Stratified, plain), UsageError) << most;
  }
  SamplingRequest same;
  same.maxSpp = 16;
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, same).ends, (std::vector<int>{8, 16}));
}

// A pixel with half 0 = {1, 3} and half 1 = {2, 6} in every channel, each sample `rays` rays.
PixelEstimate twoHalves(uint64_t rays = 1) {
  PixelEstimate p;
  for (float v : {1.f, 3.f}) p.half[0].add({v, v, v}, 1, rays);
  for (float v : {2.f, 6.f}) p.half[1].add({v, v, v}, 1, rays);
  return p;
}

TEST(PixelEstimate, MeanAndVarianceOfTheMeanFromTheHalves) {
  const PixelEstimate p = twoHalves();
  double mean[4], v[3];
  p.mean(mean);
  EXPECT_DOUBLE_EQ(mean[0], 3.0);  // (1 + 3 + 2 + 6) / 4
  EXPECT_DOUBLE_EQ(mean[3], 1.0);
  // Halves' means 2 and 4, n0 = n1 = 2: (2·2/16)·(2 − 4)² = 1.
  ASSERT_TRUE(p.varianceOfMean(v));
  EXPECT_DOUBLE_EQ(v[0], 1.0);
  // Unequal halves, 3 and 1 samples: means 2 and 6, weight 3·1/16: (3/16)·16 = 3.
  PixelEstimate q;
  for (float x : {1.f, 2.f, 3.f}) q.half[0].add({x, x, x}, 1, 1);
  q.half[1].add({6, 6, 6}, 1, 1);
  ASSERT_TRUE(q.varianceOfMean(v));
  EXPECT_DOUBLE_EQ(v[2], 3.0);
}

TEST(PixelEstimate, OneSampleHasNoEstimate) {
  PixelEstimate p;
  p.half[0].add({1, 1, 1}, 1, 1);
  double v[3];
  EXPECT_FALSE(p.varianceOfMean(v));
  // A pixel without an estimate never meets a target (it keeps taking samples).
  ErrorTarget t;
  t.rmse = 1e9;
  EXPECT_EQ(t.ratio(p, FrameSpread{1, 1}), std::numeric_limits<double>::infinity());
}

TEST(FrameSpread, RootMeanSquareOfThePixelsPerSampleDeviations) {
  // twoHalves(): 4 samples, MSE 1, so samples · MSE = 4; a flat pixel: 0; a one-sample pixel
  // has no estimate and is left out. sqrt((4 + 0) / 2) = √2.
  PixelEstimate flat, single;
  for (int h = 0; h < 2; ++h) flat.half[h].add({2, 2, 2}, 1, 1);
  single.half[0].add({5, 5, 5}, 1, 1);
  const FrameSpread s = FrameSpread::of({twoHalves(), flat, single});
  EXPECT_DOUBLE_EQ(s.deviation, std::sqrt(2.0));
  // Relative: twoHalves() has relMSE 1 / (9 + 0.01), so 4 / 9.01 over the two pixels.
  EXPECT_DOUBLE_EQ(s.relativeDeviation, std::sqrt(4 / 9.01 / 2));
  // No estimates at all: no spread (every pixel then meets its share at the first pass).
  EXPECT_EQ(FrameSpread::of({single}).deviation, 0.0);
}

TEST(ErrorTarget, RatioOfThePixelsErrorToItsShareOfTheTarget) {
  // twoHalves(): variance of the mean 1 per channel over n = 4 samples, mean 3; its per-sample
  // deviation is σ = √(4 · 1) = 2, σ / n = 0.5.
  const PixelEstimate p = twoHalves();
  ErrorTarget t;
  t.rmse = 0.5;
  // In a frame of pixels like it (spread 2), its share is the target itself: 1 / 0.5² = 4.
  EXPECT_DOUBLE_EQ(t.ratio(p, FrameSpread{2, 0}), 4.0);
  // In a frame that spreads half as much, a pixel this noisy may keep twice the squared error:
  // 0.5 · 1 / 0.25 = 2.
  EXPECT_DOUBLE_EQ(t.ratio(p, FrameSpread{1, 0}), 2.0);
  // relMSE 1 / 9.01 in a frame of pixels like it (spread √(4 / 9.01)): its relMSE over the
  // target 0.05.
  const FrameSpread same{2, std::sqrt(4 / 9.01)};
  ErrorTarget rel;
  rel.relmse = 0.05;
  EXPECT_DOUBLE_EQ(rel.ratio(p, same), 1 / 9.01 / 0.05);
  // Both: the larger.
  rel.rmse = 0.5;
  EXPECT_DOUBLE_EQ(rel.ratio(p, same), 4.0);
}

TEST(PixelEstimate, RaysPerSampleIsWhatASampleCostOnAverage) {
  PixelEstimate p;
  p.half[0].add({1, 1, 1}, 1, 1);  // a camera ray that missed
  p.half[0].add({1, 1, 1}, 1, 7);  // one that hit, lit by 4 shadow rays, reflected twice
  p.half[1].add({1, 1, 1}, 1, 4);
  EXPECT_DOUBLE_EQ(p.raysPerSample(), 4.0);                // 12 rays over 3 samples
  EXPECT_DOUBLE_EQ(PixelEstimate{}.raysPerSample(), 1.0);  // no samples: the camera ray's
}

TEST(ErrorTarget, ACostlyPixelsShareWeighsItsNoiseAgainstItsCost) {
  // Neyman's allocation with costs: n ∝ σ/√c. twoHalves() at 4 rays a sample is as noisy as at
  // one ray (σ / n = 0.5) but stops at half the samples for the same noise: ratio
  // 0.5 / √4 · s / E² = 2 where one ray a sample gives 4 (in a frame of spread 2).
  ErrorTarget t;
  t.rmse = 0.5;
  EXPECT_DOUBLE_EQ(t.ratio(twoHalves(4), FrameSpread{2, 0}), 2.0);
  // The spread weighs each probe by its cost the same way: √(4 · 1 · 4) over one pixel = 4.
  EXPECT_DOUBLE_EQ(FrameSpread::of({twoHalves(4)}).deviation, 4.0);
  // So in a frame of pixels like it (spread 4), its share is the target itself, as at one ray:
  // 0.5 / 2 · 4 / 0.25.
  EXPECT_DOUBLE_EQ(t.ratio(twoHalves(4), FrameSpread::of({twoHalves(4)})), 4.0);
}

TEST(PassPlan, AdaptiveChoiceTakesTheWorstOfEachPixelsNeighbourhood) {
  SamplingRequest r;
  r.target.rmse = 1.5;  // ratio of twoHalves() in a frame of its like: 1 / 2.25 = 0.44
  r.minSpp = 4;
  r.maxSpp = 64;
  const PassPlan plan = PassPlan::make(16, SamplerKind::Sobol, r);
  // A 4 × 3 grid of quiet pixels (4 samples each), one noisy one at (1, 1), one at (3, 2)
  // with 2 samples (below --min-spp).
  std::vector<PixelEstimate> grid(12, twoHalves());
  PixelEstimate noisy;
  for (float v : {0.f, 0.f}) noisy.half[0].add({v, v, v}, 1, 1);
  // Variance of the mean (4/16)·20² = 100, σ / n = √(100 / 4) = 5: ratio 5 · 2 / 2.25 = 4.4.
  for (float v : {20.f, 20.f}) noisy.half[1].add({v, v, v}, 1, 1);
  grid[5] = noisy;
  PixelEstimate young;
  young.half[0].add({1, 1, 1}, 1, 1);
  young.half[1].add({1, 1, 1}, 1, 1);
  grid[11] = young;
  std::vector<uint8_t> sampled;
  const FrameSpread spread{2, 0};  // as if the frame were all like twoHalves()
  ChoiceCache fresh;
  EXPECT_EQ(plan.choosePixels(grid, 4, 8, spread, fresh, sampled), 10);
  // The noisy pixel and its 8 neighbours (their neighbourhoods' worst is its 4.4, though a
  // neighbourhood's mean, (4.4 + 8 · 0.44) / 9 = 0.89, would not be),
  // and the young pixel; not (3, 0) and (3, 1)... whose neighbourhoods miss (1, 1).
  const std::vector<uint8_t> expected = {1, 1, 1, 0,  //
                                         1, 1, 1, 0,  //
                                         1, 1, 1, 1};
  EXPECT_EQ(sampled, expected);
  // A pass that every pixel has reached samples none.
  EXPECT_EQ(plan.choosePixels(grid, 4, 2, spread, fresh, sampled), 0);
}

// n samples of one value in each half: the halves agree, so the estimate reads zero.
PixelEstimate flatPixel(float value, int n) {
  PixelEstimate p;
  for (int h = 0; h < 2; ++h)
    for (int i = 0; i < n / 2; ++i) p.half[h].add({value, value, value}, 1, 1);
  return p;
}

TEST(PixelError, EdgeFloorIsTheTypicalStratifiedVarianceForTheContrastTheNeighboursShow) {
  // 16 samples, contrast 0.8 on every channel: 0.8² / (4 · 16^{3/2}) = 0.64 / 256 = 0.0025;
  // relMSE over value 0.5: 0.0025 / (0.25 + 0.01). (1e-12: the rounding of 0.8².)
  const double contrast[3] = {0.8, 0.8, 0.8};
  const PixelError e = PixelError::edgeFloor(flatPixel(0.5f, 16), contrast);
  EXPECT_NEAR(e.mse, 0.0025, 1e-12);
  EXPECT_NEAR(e.relmse, 0.0025 / 0.26, 1e-12);
  // Four times the samples: an eighth of the variance (n^{3/2}).
  EXPECT_NEAR(PixelError::edgeFloor(flatPixel(0.5f, 64), contrast).mse, 0.0025 / 8, 1e-12);
  // A channel without contrast adds nothing: the mean over channels is a third.
  const double red[3] = {0.8, 0, 0};
  EXPECT_NEAR(PixelError::edgeFloor(flatPixel(0.5f, 16), red).mse, 0.0025 / 3, 1e-12);
}

TEST(PassPlan, AnEdgeWhoseHalvesAgreeKeepsSamplingByItsFloor) {
  // A 4 × 3 frame, columns 0-1 at 0.1 and 2-3 at 0.9, 16 samples each, both halves alike: the
  // halves read zero everywhere. The edge between columns 1 and 2 (contrast 0.8) gives those
  // columns a floor of mse 0.0025 (above); with spread 1, ratio √(0.0025 / 16) / E².
  std::vector<PixelEstimate> grid;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) grid.push_back(flatPixel(x < 2 ? 0.1f : 0.9f, 16));
  SamplingRequest r;
  r.minSpp = 16;
  r.maxSpp = 64;
  r.target.rmse = 0.1;  // ratio 0.0125 / 0.01 = 1.25: the edge's columns sample on
  std::vector<uint8_t> sampled;
  ChoiceCache first, second;  // one for each plan
  EXPECT_EQ(
      PassPlan::make(64, SamplerKind::Sobol, r).choosePixels(grid, 4, 32, {1, 0}, first, sampled),
      6);
  const std::vector<uint8_t> edge = {0, 1, 1, 0,  //
                                     0, 1, 1, 0,  //
                                     0, 1, 1, 0};
  EXPECT_EQ(sampled, edge);
  r.target.rmse = 0.2;  // ratio 0.0125 / 0.04 = 0.31: met
  EXPECT_EQ(
      PassPlan::make(64, SamplerKind::Sobol, r).choosePixels(grid, 4, 32, {1, 0}, second, sampled),
      0);
}

// Passes of 8 to 64 samples to a target RMSE.
PassPlan adaptivePlan(double targetRmse) {
  SamplingRequest r;
  r.minSpp = 8;
  r.maxSpp = 64;
  r.target.rmse = targetRmse;
  return PassPlan::make(64, SamplerKind::Sobol, r);
}

TEST(PassPlan, KeptInputsChooseAsInputsTakenAfresh) {
  // A 16 x 12 frame of pixels (fixed seed), 8 samples each, one in 23 ten times as noisy (60
  // pixels chosen around them). A pass adds 8 bright samples to the pixels chosen; the next
  // choice, from the inputs kept by the first, must be the one taken afresh, bit for bit, though
  // only the pixels whose samples moved have their ratios recomputed (and their 4-neighbours
  // their edge ratios).
  const int width = 16, height = 12;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  const auto addSamples = [&](PixelEstimate& p, int n, float scale) {
    for (int i = 0; i < n; ++i) {
      const float v = scale * unit(rng);
      p.half[i % 2].add({v, v * 0.5f, 1 - v}, 1, 1 + i % 3);
    }
  };
  std::vector<PixelEstimate> grid(size_t(width) * height);
  for (size_t p = 0; p < grid.size(); ++p) addSamples(grid[p], 8, p % 23 == 0 ? 2.f : 0.2f);
  const PassPlan plan = adaptivePlan(0.05);
  const FrameSpread spread = FrameSpread::of(grid);
  ChoiceCache kept;
  std::vector<uint8_t> first, again, fresh;
  // Not all and not none (60 of 192 with this seed): the test needs pixels that move and pixels
  // that do not.
  ASSERT_EQ(plan.choosePixels(grid, width, 16, spread, kept, first), 60);
  for (size_t p = 0; p < grid.size(); ++p)
    if (first[p])
      for (int i = 0; i < 8; ++i) grid[p].half[i % 2].add({3, 3, 3}, 1, 1);
  ChoiceCache none;
  EXPECT_EQ(plan.choosePixels(grid, width, 32, spread, kept, again),
            plan.choosePixels(grid, width, 32, spread, none, fresh));
  EXPECT_EQ(again, fresh);
  // The bright samples moved the choice: 112 pixels, most of them on the edges the chosen
  // pixels' new means make with their unchosen 4-neighbours, whose own states did not move (a
  // cache that refreshed only the moved pixels' edge ratios chose 52).
  EXPECT_EQ(std::count(again.begin(), again.end(), 1), 112);
  // Another spread (as after the probes' pass) takes every ratio anew.
  const FrameSpread wider{2 * spread.deviation, 0};
  ChoiceCache none2;
  EXPECT_EQ(plan.choosePixels(grid, width, 32, wider, kept, again),
            plan.choosePixels(grid, width, 32, wider, none2, fresh));
  EXPECT_EQ(again, fresh);
}

TEST(ProbeLattice, AboutTwoHundredFiftySixProbesAtMostOneInSixtyFour) {
  // 140 × 90: 12600 / 256 = 49.2 pixels per probe, stride 7 from 3: 20 × 13 probes.
  const ProbeLattice small = ProbeLattice::of(140, 90);
  EXPECT_EQ(small.stride, 7);
  EXPECT_EQ(small.offset, 3);
  EXPECT_EQ(small.columns, 20);  // x = 3, 10, ..., 136
  EXPECT_EQ(small.rows, 13);     // y = 3, 10, ..., 87
  // 1920 × 1080: the stride stops at 8, 240 × 135 probes.
  const ProbeLattice hd = ProbeLattice::of(1920, 1080);
  EXPECT_EQ(hd.stride, 8);
  EXPECT_EQ(hd.columns, 240);
  EXPECT_EQ(hd.rows, 135);
  // A frame smaller than 256 pixels probes every pixel.
  const ProbeLattice tiny = ProbeLattice::of(10, 3);
  EXPECT_EQ(tiny.stride, 1);
  EXPECT_EQ(tiny.columns * tiny.rows, 30);
}

TEST(FrameError, AveragesPixelsLikeCompareAndIsAbsentForRegularGrids) {
  const std::vector<PixelEstimate> pixels = {twoHalves(), twoHalves()};
  const FrameError e = estimateFrameError(pixels, SamplerKind::Stratified);
  ASSERT_TRUE(e.rmse && e.relmse);
  EXPECT_DOUBLE_EQ(*e.rmse, 1.0);                 // every channel's variance is 1
  EXPECT_DOUBLE_EQ(*e.relmse, 1.0 / (9 + 0.01));  // 1 / (mean² + ε)
  EXPECT_FALSE(estimateFrameError(pixels, SamplerKind::Regular).rmse);
}

TEST(FrameError, SameBitsAndChoicesForAnyThreadCount) {
  // The statistics and choices run on the render's threads. A 320 x 200 frame (16 of the
  // reduction's 4096-pixel blocks, fixed seed) must give the same estimate, bit for bit, and the
  // same choice on 1 thread as on 4: the render's bytes may not depend on the thread count. An
  // ordinary parallel sum, split where threads steal work, would differ in its last bits.
  const int width = 320, height = 200;
  std::mt19937 rng(11);
  std::lognormal_distribution<float> radiance(0.f, 2.f);
  std::vector<PixelEstimate> grid(size_t(width) * height);
  for (PixelEstimate& p : grid)
    for (int i = 0; i < 8; ++i) {
      const float v = radiance(rng);
      p.half[i % 2].add({v, 0.5f * v, 1.f}, 1, 1 + i % 3);
    }
  const PassPlan plan = adaptivePlan(10);
  const FrameSpread spread = FrameSpread::of(grid);
  const auto run = [&](int threads, FrameError& error, std::vector<uint8_t>& chosen) {
    int64_t count = 0;
    withThreads(threads, [&] {
      error = estimateFrameError(grid, SamplerKind::Sobol);
      ChoiceCache kept;
      count = plan.choosePixels(grid, width, 16, spread, kept, chosen);
    });
    return count;
  };
  FrameError one, four;
  std::vector<uint8_t> chosenOne, chosenFour;
  const int64_t countOne = run(1, one, chosenOne);
  ASSERT_TRUE(one.rmse && one.relmse);
  for (int attempt = 0; attempt < 5; ++attempt) {  // stealing differs from run to run
    ASSERT_EQ(run(4, four, chosenFour), countOne);
    EXPECT_EQ(*four.rmse, *one.rmse);
    EXPECT_EQ(*four.relmse, *one.relmse);
    EXPECT_EQ(chosenFour, chosenOne);
  }
  // About half of the pixels chosen with this seed and target, so that the choice compared is
  // a real one.
  EXPECT_EQ(countOne, 29838);
}

// What `glint render` announces (PassPlan::describe): under a time limit, the limit and the most
// samples, not the scene's spp ("--time-limit 3 --max-spp 4096" said "at 16 spp").
TEST(PassPlan, DescribesWhatTheRenderWillDo) {
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, {}).describe(), "at 16 spp");
  SamplingRequest timed;
  timed.timeLimitSeconds = 3;
  timed.maxSpp = 4096;
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, timed).describe(),
            "for at most 3 s, up to 4096 spp (a first pass of 8 spp always finishes)");
  SamplingRequest adaptive;
  adaptive.target.rmse = 0.01;
  adaptive.maxSpp = 256;
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, adaptive).describe(),
            "until the estimated RMSE is at most 0.01, 8 to 256 spp per pixel");
  adaptive.target.relmse = 0.002;
  adaptive.timeLimitSeconds = 1.5;
  adaptive.minSpp = 4;
  EXPECT_EQ(PassPlan::make(16, SamplerKind::Stratified, adaptive).describe(),
            "until the estimated RMSE is at most 0.01 and the relMSE is at most 0.002, 4 to 256 "
            "spp per pixel, for at most 1.5 s");
}

}  // namespace
}  // namespace glint
