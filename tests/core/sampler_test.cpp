#include "core/sampler.h"

#include "core/cpu_features.h"
#include "core/fast_divide.h"
#include "core/hash.h"
#include "core/lanes.h"
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <set>
#include <string>
#include <vector>

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

// Runs `draw` once with each width of lanes this CPU draws runs of points in (setSamplerLanes: 8,
// and 16 with AVX-512), then goes back to the widest: the points must not depend on the width,
// and an AVX-512 machine must test the eight lanes too.
template <class Draw>
void withEveryLaneWidth(const Draw& draw) {
  struct Restore {
    int width = samplerLanes();
    ~Restore() { setSamplerLanes(width); }
  } restore;  // also when a draw throws
  for (const int width : {8, 16}) {
    if (!setSamplerLanes(width)) continue;
    SCOPED_TRACE("in " + std::to_string(width) + " lanes");
    draw();
  }
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

// The camera maps four lens points at once (camera.cpp): each lane must be the scalar map's
// bits, on the grid above (both wedges, the diagonals where |ox| = |oy|, the centre) and at
// points a float's ulp from them, or a thin lens's image would change with how samples fall
// into lanes.
TEST(Sampling, ConcentricMapLanesEqualOnePointAtATime) {
  using F32x4 = float __attribute__((vector_size(16)));
  std::vector<Vec2f> points;
  for (int i = 0; i <= 64; ++i)
    for (int j = 0; j <= 64; ++j) {
      const float x = static_cast<float>(i) / 64, y = static_cast<float>(j) / 64;
      points.push_back({x, y});
      points.push_back({std::nextafter(x, 1.0f), y});
      points.push_back({x, std::nextafter(y, 0.0f)});
    }
  for (uint32_t k = 0; k < 4096; ++k) {
    const uint64_t h = mix64(k);
    points.push_back({toUnitFloat(h), toUnitFloat(h << 32)});
  }
  while (points.size() % 4 != 0) points.push_back({0.5f, 0.5f});
  for (size_t i = 0; i < points.size(); i += 4) {
    F32x4 ux, uy, dx, dy;
    for (int l = 0; l < 4; ++l) ux[l] = points[i + size_t(l)].x, uy[l] = points[i + size_t(l)].y;
    squareToDiskConcentricLanes(ux, uy, dx, dy);
    for (int l = 0; l < 4; ++l) {
      const Vec2f u = points[i + size_t(l)], d = squareToDiskConcentric(u);
      EXPECT_EQ(std::bit_cast<uint32_t>(dx[l]), std::bit_cast<uint32_t>(d.x)) << u.x << ", " << u.y;
      EXPECT_EQ(std::bit_cast<uint32_t>(dy[l]), std::bit_cast<uint32_t>(d.y)) << u.x << ", " << u.y;
    }
  }
}

// Sample `index` of dimension `dim` in pixel (px, py), `sub` of `count` sub-samples.
Vec2f sampleOf(const Sampler& s, int px, int py, int index, uint32_t dim, int sub = 0,
               int count = 1) {
  return s.get2D(s.pattern(s.pixelKey(px, py), dim), index, sub, count);
}
Vec2f pixelSample(const Sampler& s, int px, int py, int index) {
  return sampleOf(s, px, py, index, dimension(Dim::Pixel));
}

TEST(FastDivisor, LanesMatchOneDividendAtATime) {
  // The sampler divides eight lanes at once (core/lanes.h) with 32 × 32-bit products in place
  // of one 64 × 64; every lane must give what integer division gives.
  for (uint32_t d : {1u, 3u, 7u, 64u, 1000u, 4099u, 65537u, 0x7fffffffu, 0xffffffffu}) {
    const FastDivisor f(d);
    for (uint32_t block = 0; block < 64; ++block) {
      U32x8 a;
      for (int l = 0; l < 8; ++l)
        a[l] = block == 0 ? 0xffffffffu - static_cast<uint32_t>(l)
                          : static_cast<uint32_t>(mix64(block * 8ull + static_cast<uint64_t>(l)));
      const U32x8 q = f.quotient(a), r = f.remainder(a);
      for (int l = 0; l < 8; ++l) {
        ASSERT_EQ(q[l], a[l] / d) << a[l] << " / " << d;
        ASSERT_EQ(r[l], a[l] % d) << a[l] << " % " << d;
      }
    }
  }
}

TEST(Sampler, SeedAndPixelChangeThePattern) {
  const Sampler a(SamplerKind::Stratified, 16, 7), b(SamplerKind::Stratified, 16, 8);
  EXPECT_NE(pixelSample(a, 3, 9, 0).x, pixelSample(b, 3, 9, 0).x);
  EXPECT_NE(pixelSample(a, 3, 9, 0).x, pixelSample(a, 4, 9, 0).x);
}

class StratifiedCounts : public ::testing::TestWithParam<int> {};

TEST_P(StratifiedCounts, EachOneDimensionalStratumHoldsOneSample) {
  // Correlated multi-jitter stratifies both 1D projections into spp strata, for any spp.
  const int spp = GetParam();
  const Sampler s(SamplerKind::Stratified, spp, 1);
  for (int px = 0; px < 20; ++px) {
    std::vector<float> xs, ys;
    for (int i = 0; i < spp; ++i) {
      const Vec2f u = pixelSample(s, px, 5, i);
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
  }
}

// Powers of two, squares, non-squares, a prime (4099: a 1 × 4099 grid) and sets whose
// permutations cycle-walk (sizes just above a power of two: 4097, 1000).
INSTANTIATE_TEST_SUITE_P(Counts, StratifiedCounts,
                         ::testing::Values(1, 2, 4, 7, 8, 9, 12, 16, 32, 50, 64, 128, 1000, 4096,
                                           4097, 4099));

TEST(Sampler, DrawsInEveryLaneWidthTheCpuRuns) {
  // Eight lanes run everywhere (baseline x86-64 or AVX2); sixteen where the CPU has AVX-512 F,
  // DQ and VL, which their code is built for; no other width is drawn in.
  const int widest = samplerLanes();
  const bool avx512 = cpuFeatures().avx512FDqVl();
  EXPECT_EQ(widest, avx512 ? 16 : 8);
  EXPECT_TRUE(setSamplerLanes(8));
  EXPECT_EQ(samplerLanes(), 8);
  EXPECT_EQ(setSamplerLanes(16), avx512);
  EXPECT_EQ(samplerLanes(), avx512 ? 16 : 8);
  EXPECT_FALSE(setSamplerLanes(4));
  EXPECT_FALSE(setSamplerLanes(32));
  EXPECT_TRUE(setSamplerLanes(widest));
}

TEST(Sampler, LanesMatchOnePointAtATime) {
  // Runs of three or more points are drawn eight side by side, or sixteen where the CPU has
  // AVX-512 (each width the CPU runs is tried), a last block of eight or fewer in eight
  // (sampler.cpp: vector lanes, where a permutation's cycle walking continues only in the lanes
  // still outside its domain); one or two points are drawn alone. Both must give the same bits, for
  // every kind, for sets of any size (powers of two up to 2^28, where rounding to float often lands
  // on a stratum's edge and steps back, and sizes that are not), for runs that start anywhere and
  // end mid-block (13 and 29: a last block of more than eight; 40: of eight).
  withEveryLaneWidth([] {
    std::vector<int> sizes;
    for (int b = 0; b <= 28; ++b) sizes.push_back(1 << b);
    for (int n : {3, 9, 12, 50, 1000, 4097, 4099, 99991, (1 << 28) - 1}) sizes.push_back(n);
    for (const SamplerKind kind :
         {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol})
      for (const int n : sizes) {
        const Sampler s(kind, n, 5);
        for (int pixel = 0; pixel < 3; ++pixel)
          for (const uint32_t dim : {dimension(Dim::Pixel), dimension(Dim::Light, 1, 2)}) {
            const SamplePattern pattern = s.pattern(s.pixelKey(pixel, 9), dim);
            const uint64_t spread = hashKey(static_cast<uint64_t>(n), static_cast<uint64_t>(pixel));
            for (const int size : {3, 8, 13, 29, 40}) {
              const int first = n <= size ? 0 : static_cast<int>(spread % uint64_t(n - size));
              const int count = std::min(size, n - first);
              Vec2f together[40];
              s.get2D(pattern, first, 0, count, 1, together);
              for (int j = 0; j < count; ++j) {
                const Vec2f alone = s.get2D(pattern, first + j);
                ASSERT_EQ(alone.x, together[j].x)
                    << samplerName(kind) << " n " << n << " point " << first + j;
                ASSERT_EQ(alone.y, together[j].y)
                    << samplerName(kind) << " n " << n << " point " << first + j;
              }
            }
          }
      }
  });
}

TEST(Sampler, SubSampleRunsContinueIntoTheNextSample) {
  // A run of sub-samples is drawn by flat index index·count + sub, so a run that passes the
  // last sub-sample of one camera sample goes on with the next sample's first.
  withEveryLaneWidth([] {
    const Sampler s(SamplerKind::Stratified, 9, 4);
    const SamplePattern pattern = s.pattern(s.pixelKey(7, 2), dimension(Dim::Light, 1, 2));
    Vec2f run[7];
    s.get2D(pattern, 3, 5, 7, 6, run);  // sample 3's sub-samples 5 .. 11 of 6
    for (int j = 0; j < 7; ++j) {
      const Vec2f alone = s.get2D(pattern, 3 + (5 + j) / 6, (5 + j) % 6, 6);
      EXPECT_EQ(alone.x, run[j].x) << j;
      EXPECT_EQ(alone.y, run[j].y) << j;
    }
  });
}

TEST(Sampler, PointsOfSeveralPixelsSetsDrawnTogetherMatchOnePointAtATime) {
  // get2DAt draws blocks of eight (or sixteen) lanes whose points come from different pixels'
  // sets, each lane with its own keys (sampler.cpp); each point must be what it is drawn alone,
  // for every kind, for sets of many sizes (both halves of an odd spp differ in size, which
  // splits the lanes into runs), for points anywhere in their sets, in runs ending mid-block
  // (the lanes' tail repeats the last point) and of every length up to a few blocks.
  withEveryLaneWidth([] {
    for (const SamplerKind kind :
         {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol})
      for (const int spp : {1, 2, 3, 4, 7, 16, 33, 64, 1000, 4097}) {
        const Sampler s(kind, spp, 11);
        for (const int count : {1, 3, 4, 8}) {
          constexpr int kMost = 29;
          SamplePattern patterns[kMost];
          const SamplePattern* of[kMost];
          uint32_t flat[kMost];
          for (int j = 0; j < kMost; ++j) {
            // Pixels change every few points, halves (and so set sizes) every third; the camera
            // dimension too, where a regular sampler's cell centres are drawn one at a time.
            const uint64_t spread = hashKey(uint64_t(spp), uint64_t(count), uint64_t(j));
            const int half = spp == 1 ? 0 : (j / 3) % 2;
            const uint32_t dim = j % 11 == 10 ? dimension(Dim::Pixel) : dimension(Dim::Light, 1, 2);
            patterns[j] = s.pattern(s.pixelKey(j / 4, 3), dim, half);
            of[j] = &patterns[j];
            flat[j] = static_cast<uint32_t>(spread % (uint64_t(patterns[j].samples) * count));
          }
          for (int size = 0; size <= kMost; ++size) {
            Vec2f together[kMost];
            s.get2DAt(of, count, flat, size, together);
            for (int j = 0; j < size; ++j) {
              const Vec2f alone = s.get2D(patterns[j], static_cast<int>(flat[j]) / count,
                                          static_cast<int>(flat[j]) % count, count);
              ASSERT_EQ(alone.x, together[j].x)
                  << samplerName(kind) << " spp " << spp << " count " << count << " point " << j;
              ASSERT_EQ(alone.y, together[j].y)
                  << samplerName(kind) << " spp " << spp << " count " << count << " point " << j;
            }
          }
        }
      }
  });
}

TEST(Sampler, SubSampleStreamGoesSampleBySampleThroughEverySubSample) {
  // The stream gives each sample's sub-samples in order, then the next sample's, whatever
  // windows it draws them in: 30 samples of 5 sub-samples cross its window of 64 twice.
  withEveryLaneWidth([] {
    const Sampler s(SamplerKind::Stratified, 8, 2);
    constexpr int kSamples = 30, kCount = 5;
    SamplePattern patterns[kSamples];
    int indices[kSamples];
    for (int k = 0; k < kSamples; ++k) {
      patterns[k] = s.pattern(s.pixelKey(k / 7, 1), dimension(Dim::Light, 0, 1), k % 2);
      indices[k] = (k * 3) % 4;
    }
    SubSampleStream stream(s, kCount, patterns, indices, kSamples);
    for (int k = 0; k < kSamples; ++k)
      for (int sub = 0; sub < kCount; ++sub) {
        const Vec2f expected = s.get2D(patterns[k], indices[k], sub, kCount);
        const Vec2f got = stream.next();
        ASSERT_EQ(expected.x, got.x) << k << " " << sub;
        ASSERT_EQ(expected.y, got.y) << k << " " << sub;
      }
  });
}

TEST(Sampler, RegularIsCellCentresInThePixelDimensionOnly) {
  // spp = 4 → a 2 × 2 grid of centres at 0.25 and 0.75, row by row.
  const Sampler s(SamplerKind::Regular, 4, 0);
  const Vec2f expected[4] = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0.75f, 0.75f}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(pixelSample(s, 5, 1, i).x, expected[i].x) << i;
    EXPECT_EQ(pixelSample(s, 5, 1, i).y, expected[i].y) << i;
  }
  // Other dimensions of a regular render are stratified: not all on the centres' 1/4 grid.
  std::set<float> lens;
  for (int i = 0; i < 4; ++i) lens.insert(sampleOf(s, 5, 1, i, dimension(Dim::Lens)).x);
  for (float c : {0.25f, 0.75f}) lens.erase(c);
  EXPECT_EQ(lens.size(), 4u);
  for (int c : strataCounts(std::vector<float>(lens.begin(), lens.end()), 4)) EXPECT_EQ(c, 1);
}

TEST(Sampler, OtherDimensionsAreStratifiedAcrossTheirSubsamples) {
  // 4 camera samples × 4 light samples = 16 points, one per 1D stratum of width 1/16.
  const Sampler s(SamplerKind::Stratified, 4, 3);
  std::vector<float> xs;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) xs.push_back(sampleOf(s, 2, 2, i, 16, j, 4).x);
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
      for (int i = 0; i < n; ++i) pts.push_back(pixelSample(s, px, 3, i));
      for (int j = 0; j <= m; ++j) {
        std::set<std::pair<int, int>> cells;
        for (const Vec2f& p : pts)
          cells.insert({int(p.x * float(1 << j)), int(p.y * float(1 << (m - j)))});
        EXPECT_EQ(cells.size(), size_t(n)) << "m = " << m << ", shape 2^-" << j << " pixel " << px;
      }
      // The light/lens dimensions are nets too, over spp × count points.
      std::set<int> strata;
      for (int i = 0; i < n; ++i) strata.insert(stratumOf(sampleOf(s, px, 3, i, 40).x, n));
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
        const double a = pixelSample(s, px, 0, i).x;
        const double b = sampleOf(s, px, 0, i, dimension(Dim::Lens)).x;
        sx += a, sy += b, sxx += a * a, syy += b * b, sxy += a * b, ++n;
      }
    const double cov = sxy / n - (sx / n) * (sy / n);
    const double rho = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    EXPECT_LT(std::fabs(rho), 3 / std::sqrt(1024.0)) << samplerName(kind);
  }
}

}  // namespace
}  // namespace glint
