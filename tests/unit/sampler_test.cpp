#include "core/sampler.h"

#include <gtest/gtest.h>

#include <set>

namespace glint {
namespace {

// Counts samples per 1D stratum of width 1/n; a stratified set has exactly one in each.
std::vector<int> strataCounts(const std::vector<float>& xs, int n) {
  std::vector<int> c(static_cast<size_t>(n), 0);
  for (float x : xs) ++c[static_cast<size_t>(x * float(n))];
  return c;
}

TEST(Sampler, SameKeySameNumbers) {
  const Sampler a(SamplerKind::Stratified, 16, 7), b(SamplerKind::Stratified, 16, 7);
  for (int s = 0; s < 16; ++s) {
    EXPECT_EQ(a.pixelSample(3, 9, s).x, b.pixelSample(3, 9, s).x);
    EXPECT_EQ(a.get2D(3, 9, s, 20).y, b.get2D(3, 9, s, 20).y);
  }
}

TEST(Sampler, SeedAndPixelChangeThePattern) {
  const Sampler a(SamplerKind::Stratified, 16, 7), b(SamplerKind::Stratified, 16, 8);
  EXPECT_NE(a.pixelSample(3, 9, 0).x, b.pixelSample(3, 9, 0).x);
  EXPECT_NE(a.pixelSample(3, 9, 0).x, a.pixelSample(4, 9, 0).x);
}

class StratifiedCounts : public ::testing::TestWithParam<int> {};

TEST_P(StratifiedCounts, EachOneDimensionalStratumHoldsOneSample) {
  // Correlated multi-jitter stratifies both 1D projections into spp strata, for any spp.
  const int spp = GetParam();
  const Sampler s(SamplerKind::Stratified, spp, 1);
  for (int px = 0; px < 20; ++px) {
    std::vector<float> xs, ys;
    for (int i = 0; i < spp; ++i) {
      const Vec2f u = s.pixelSample(px, 5, i);
      ASSERT_GE(u.x, 0.0f);
      ASSERT_LT(u.x, 1.0f);
      ASSERT_GE(u.y, 0.0f);
      ASSERT_LT(u.y, 1.0f);
      xs.push_back(u.x);
      ys.push_back(u.y);
    }
    const int m = static_cast<int>(std::floor(std::sqrt(double(spp))));
    const int k = (spp + m - 1) / m;
    if (m * k == spp) {
      for (int c : strataCounts(xs, spp)) EXPECT_EQ(c, 1);
      for (int c : strataCounts(ys, spp)) EXPECT_EQ(c, 1);
    }
    // Always: at most one sample per cell of the m × k grid.
    std::set<std::pair<int, int>> cells;
    for (int i = 0; i < spp; ++i)
      EXPECT_TRUE(
          cells.insert({int(xs[size_t(i)] * float(m)), int(ys[size_t(i)] * float(k))}).second);
  }
}

INSTANTIATE_TEST_SUITE_P(Counts, StratifiedCounts, ::testing::Values(1, 2, 4, 8, 9, 16, 12, 64));

TEST(Sampler, RegularIsCellCentres) {
  // spp = 4 → a 2 × 2 grid of centres at 0.25 and 0.75.
  const Sampler s(SamplerKind::Regular, 4, 0);
  EXPECT_EQ(s.pixelSample(0, 0, 0).x, 0.25f);
  EXPECT_EQ(s.pixelSample(0, 0, 1).x, 0.75f);
  EXPECT_EQ(s.pixelSample(0, 0, 2).y, 0.75f);
}

TEST(Sampler, OtherDimensionsAreStratifiedAcrossTheirSubsamples) {
  // 4 camera samples × 4 light samples = 16 points, one per 1D stratum of width 1/16.
  const Sampler s(SamplerKind::Stratified, 4, 3);
  std::vector<float> xs;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) xs.push_back(s.get2D(2, 2, i, 16, j, 4).x);
  for (int c : strataCounts(xs, 16)) EXPECT_EQ(c, 1);
}

}  // namespace
}  // namespace glint
