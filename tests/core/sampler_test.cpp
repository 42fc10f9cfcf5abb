#include "core/sampler.h"

#include "core/fast_divide.h"
#include "core/hash.h"
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <set>

namespace glint {
namespace {

// The stratum of width 1/n that holds x: ⌊x·n⌋, exact in double (a float product could round
// a value just below a stratum's edge onto it).
int stratumOf(float x, int n) { return static_cast<int>(double(x) * n); }

// Counts samples per 1D stratum of width 1/n; a stratified set has exactly one in each.
std::vector<int> strataCounts(const std::vector<float>& xs, int n) {
  std::vector<int> c(static_cast<size_t>(n), 0);
  for (float x : xs) ++c[static_cast<size_t>(stratumOf(x, n))];
  return c;
}

TEST(FastDivisor, MatchesIntegerDivisionForEveryDividendTried) {
  // The sampler's strata depend on these being exact: Lemire's method is exact for all 32-bit
  // dividends, so any mismatch is a bug. Divisors 1..4096 and some large ones, dividends at the
  // edges of the 32-bit range, around multiples of d, and a hashed spread.
  std::vector<uint32_t> divisors;
  for (uint32_t d = 1; d <= 4096; ++d) divisors.push_back(d);
  for (uint32_t d : {65535u, 65536u, 65537u, 1000003u, 0x7fffffffu, 0x80000000u, 0xffffffffu})
    divisors.push_back(d);
  for (uint32_t d : divisors) {
    const FastDivisor f(d);
    std::vector<uint32_t> as = {0,
                                1,
                                d - 1,
                                d,
                                d + 1,
                                0x7fffffffu,
                                0x80000000u,
                                0xfffffffeu,
                                0xffffffffu,
                                0xffffffffu / d * d,
                                0xffffffffu / d * d - 1};
    for (uint32_t i = 0; i < 64; ++i) as.push_back(static_cast<uint32_t>(mix64(d * 64ull + i)));
    for (uint32_t a : as) {
      ASSERT_EQ(f.quotient(a), a / d) << a << " / " << d;
      ASSERT_EQ(f.remainder(a), a % d) << a << " % " << d;
    }
  }
}

TEST(Sampling, QuarterPiSineAndCosineAreWithinFloatRounding) {
  // The series' truncation error is below 2e-9; what remains is float rounding of a few terms.
  for (int i = -1000; i <= 1000; ++i) {
    const double phi = (kPi / 4) * static_cast<double>(i) / 1000.0;
    const Vec2f cs = cosSinQuarterPi(static_cast<float>(phi));
    EXPECT_NEAR(cs.x, std::cos(double(static_cast<float>(phi))), 2e-7) << phi;
    EXPECT_NEAR(cs.y, std::sin(double(static_cast<float>(phi))), 2e-7) << phi;
  }
}

TEST(Sampling, ConcentricMapMatchesItsPolarForm) {
  // Shirley–Chiu: the square's ring max(|ox|, |oy|) = r maps to the circle of radius r, and
  // the angle runs linearly along each edge of the ring (π/4 per half edge).
  for (int i = 0; i <= 64; ++i)
    for (int j = 0; j <= 64; ++j) {
      const Vec2f u{static_cast<float>(i) / 64, static_cast<float>(j) / 64};
      const double ox = 2.0 * u.x - 1, oy = 2.0 * u.y - 1;
      double r, theta;
      if (ox == 0 && oy == 0) {
        r = 0, theta = 0;
      } else if (std::fabs(ox) > std::fabs(oy)) {
        r = ox, theta = (kPi / 4) * (oy / ox);
      } else {
        r = oy, theta = kPi / 2 - (kPi / 4) * (ox / oy);
      }
      const Vec2f d = squareToDiskConcentric(u);
      EXPECT_NEAR(d.x, r * std::cos(theta), 3e-7) << u.x << ", " << u.y;
      EXPECT_NEAR(d.y, r * std::sin(theta), 3e-7) << u.x << ", " << u.y;
    }
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
    // Every 1D stratum holds exactly one sample (n-rooks) …
    for (int c : strataCounts(xs, spp)) EXPECT_EQ(c, 1);
    for (int c : strataCounts(ys, spp)) EXPECT_EQ(c, 1);
    // … and every cell of the m × k grid (m·k = spp, m the largest divisor ≤ √spp) exactly one:
    // a grid with empty cells would leave the same region of every pixel unsampled (a bias
    // that measured 7× the error at 1000 spp before this was fixed).
    int m = static_cast<int>(std::floor(std::sqrt(double(spp))));
    while (spp % m != 0) --m;
    const int k = spp / m;
    std::set<std::pair<int, int>> cells;
    for (int i = 0; i < spp; ++i)
      EXPECT_TRUE(cells.insert({stratumOf(xs[size_t(i)], m), stratumOf(ys[size_t(i)], k)}).second);
    EXPECT_EQ(cells.size(), size_t(spp));
  }
}

// 4096 is a 64 × 64 grid, the largest whose permutations the sampler caches; 4099 (prime) is
// 1 × 4099, drawn without the cache.
INSTANTIATE_TEST_SUITE_P(Counts, StratifiedCounts,
                         ::testing::Values(1, 2, 4, 7, 8, 9, 12, 16, 32, 50, 64, 128, 1000, 4096,
                                           4099));

TEST(Sampler, DrawingOrderDoesNotChangeTheNumbers) {
  // The sampler keeps recent column and row permutations per thread (sampler.cpp). Drawing 40
  // sets one after the other, and then all 40 interleaved sample by sample (which evicts and
  // refills the 16-entry table over and over), must give the same numbers bit for bit.
  const Sampler s(SamplerKind::Stratified, 16, 11);
  constexpr int kSets = 40, kCount = 4;
  std::vector<Vec2f> setBySet, interleaved;
  for (int d = 0; d < kSets; ++d)
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < kCount; ++j)
        setBySet.push_back(s.get2D(3, 5, i, dimension(Dim::Light, d % 8, d / 8), j, kCount));
  interleaved.resize(setBySet.size());
  for (int i = 0; i < 16; ++i)
    for (int d = 0; d < kSets; ++d)
      for (int j = 0; j < kCount; ++j)
        interleaved[static_cast<size_t>((d * 16 + i) * kCount + j)] =
            s.get2D(3, 5, i, dimension(Dim::Light, d % 8, d / 8), j, kCount);
  for (size_t k = 0; k < setBySet.size(); ++k) {
    EXPECT_EQ(setBySet[k].x, interleaved[k].x) << k;
    EXPECT_EQ(setBySet[k].y, interleaved[k].y) << k;
  }
}

TEST(Sampler, DrawingSubSamplesTogetherGivesTheSameNumbers) {
  // get2DFor over a range of sub-samples (how shading draws a light's samples) must equal the
  // one-at-a-time draws bit for bit, for every kind, for ranges that start anywhere.
  for (const SamplerKind kind :
       {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol}) {
    const Sampler s(kind, 9, 4);
    const SamplePattern pattern = s.pattern(s.pixelKey(7, 2), dimension(Dim::Light, 1, 2));
    constexpr int kCount = 12;
    for (int index = 0; index < 9; ++index)
      for (const auto& [first, size] : {std::pair{0, 12}, std::pair{5, 7}, std::pair{11, 1}}) {
        Vec2f together[kCount];
        s.get2DFor(pattern, index, first, size, kCount, together);
        for (int j = 0; j < size; ++j) {
          const Vec2f alone = s.get2DFor(pattern, index, first + j, kCount);
          EXPECT_EQ(alone.x, together[j].x) << samplerName(kind) << " " << index << " " << j;
          EXPECT_EQ(alone.y, together[j].y) << samplerName(kind) << " " << index << " " << j;
        }
      }
  }
}

TEST(Sampler, PowerOfTwoSetsMatchTheGeneralConstruction) {
  // Sets of n = 2^b points drawn three or more at a time take a vector path (sampler.cpp) that
  // shares no code with the general construction, which one or two points at a time take. The
  // two must agree bit for bit, for every b, for runs that start anywhere and end mid-block, and
  // for large sets, where rounding to float often lands on a stratum's edge and steps back;
  // with the AVX2 build of the path where the CPU has it, and with the portable build.
  for (const bool portable : {false, true}) {
    forcePortableSamplerLanes(portable);
    SCOPED_TRACE(portable ? "portable build" : "this CPU's build");
    for (int b = 0; b <= 28; ++b) {
      const int n = 1 << b;
      const Sampler s(SamplerKind::Stratified, n, 5);
      for (int pixel = 0; pixel < 3; ++pixel) {
        const SamplePattern pattern = s.pattern(s.pixelKey(pixel, 9), dimension(Dim::Lens));
        const uint64_t spread = hashKey(static_cast<uint64_t>(b), static_cast<uint64_t>(pixel));
        for (const int size : {3, 8, 13, 40}) {
          const int first = n <= size ? 0 : static_cast<int>(spread % uint64_t(n - size));
          const int count = std::min(size, n - first);
          if (count < 3) continue;
          Vec2f together[40];
          s.get2DFor(pattern, first, 0, count, 1, together);
          for (int j = 0; j < count; ++j) {
            const Vec2f alone = s.get2DFor(pattern, first + j);
            EXPECT_EQ(alone.x, together[j].x) << "n = 2^" << b << ", point " << first + j;
            EXPECT_EQ(alone.y, together[j].y) << "n = 2^" << b << ", point " << first + j;
          }
        }
      }
    }
  }
  forcePortableSamplerLanes(false);
}

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

TEST(Sampler, SobolPrefixesAreZeroTwoNets) {
  // A (0,m,2)-net in base 2: each of the 2^m elementary intervals of every shape
  // 2^-j × 2^-(m−j) holds exactly one of the first 2^m points — Owen scrambling of values
  // and of the index must keep this, for every pixel's own scramble.
  for (int m : {2, 4, 6, 8}) {
    const int n = 1 << m;
    const Sampler s(SamplerKind::Sobol, n, 5);
    for (int px = 0; px < 8; ++px) {
      std::vector<Vec2f> pts;
      for (int i = 0; i < n; ++i) pts.push_back(s.pixelSample(px, 3, i));
      for (int j = 0; j <= m; ++j) {
        std::set<std::pair<int, int>> cells;
        for (const Vec2f& p : pts)
          cells.insert({int(p.x * float(1 << j)), int(p.y * float(1 << (m - j)))});
        EXPECT_EQ(cells.size(), size_t(n)) << "m = " << m << ", shape 2^-" << j << " pixel " << px;
      }
      // The light/lens dimensions are nets too, over spp × count points.
      std::set<int> strata;
      for (int i = 0; i < n; ++i) strata.insert(stratumOf(s.get2D(px, 3, i, 40).x, n));
      EXPECT_EQ(strata.size(), size_t(n));
    }
  }
}

TEST(Sampler, OtherDimensionsAreNotCorrelatedWithPixelSamples) {
  // The shuffle of seed 000 §13.4.2: without it, sample i of the lens set would sit in the same
  // stratum as pixel sample i and the two would be almost perfectly correlated. Pooled Pearson
  // correlation over 64 pixels × 16 samples = 1024 pairs; for independent pairs |ρ| stays below
  // 3/√1024 ≈ 0.094 with probability 0.997.
  for (SamplerKind kind : {SamplerKind::Stratified, SamplerKind::Sobol}) {
    const Sampler s(kind, 16, 9);
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    int n = 0;
    for (int px = 0; px < 64; ++px)
      for (int i = 0; i < 16; ++i) {
        const double a = s.pixelSample(px, 0, i).x;
        const double b = s.get2D(px, 0, i, dimension(Dim::Lens)).x;
        sx += a, sy += b, sxx += a * a, syy += b * b, sxy += a * b, ++n;
      }
    const double cov = sxy / n - (sx / n) * (sy / n);
    const double rho = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    EXPECT_LT(std::fabs(rho), 3 / std::sqrt(1024.0)) << samplerName(kind);
  }
}

}  // namespace
}  // namespace glint
