// The MIP pyramid image textures are filtered through (materials/mip_pyramid.h): its levels,
// its wrap modes, and how far its filter strays from the image it filters.
#include "materials/mip_pyramid.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

MipPyramid pyramidOf(int width, int height, int channels, auto texel) {
  std::vector<float> texels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) texels.push_back(float(texel(x, y, c)));
  return MipPyramid(width, height, channels, std::move(texels));
}

float lookUp(const MipPyramid& p, Vec2f st, Vec2f a, Vec2f b, int channel = 0,
             TextureWrap wrap = TextureWrap::Repeat) {
  float v = 0;
  p.filter({st, a, b, wrap, wrap}, channel, 1, &v);
  return v;
}

TEST(MipPyramid, EachLevelIsTheBoxAverageOfTheOneAbove) {
  // 5 × 2: the next level is 2 × 1, each texel the average of 2.5 texels of the row pair
  // (the middle column split between them).
  const MipPyramid p = pyramidOf(5, 2, 1, [](int x, int y, int) { return x + 10 * y; });
  ASSERT_EQ(p.levelCount(), 3);  // 5×2, 2×1, 1×1
  EXPECT_EQ(p.levelWidth(1), 2);
  EXPECT_EQ(p.levelHeight(1), 1);
  // Rows 0 and 1 average to x + 5; columns [0, 2.5) to (0 + 1 + 2/2) / 2.5 + 5, columns
  // [2.5, 5) to (2/2 + 3 + 4) / 2.5 + 5 (float rounding: 1e-5).
  EXPECT_NEAR(p.texel(1, 0, 0, 0), 5.8, 1e-5);
  EXPECT_NEAR(p.texel(1, 1, 0, 0), 8.2, 1e-5);
  EXPECT_NEAR(p.texel(2, 0, 0, 0), 7, 1e-5);  // the whole image's mean
  // Bytes: 10 + 2 + 1 texels of one float, and a padding float per level.
  EXPECT_EQ(MipPyramid::bytesFor(5, 2, 1), (13 + 3) * 4.0);
}

TEST(MipPyramid, BytesForIsWhatThePyramidHolds) {
  // A texture's memory is checked against bytesFor before its file is read: it must be what
  // the levels then hold, padding floats included, to the byte. Odd and even sides, strips,
  // one texel, and every channel count.
  for (const auto& [w, h, c] : {std::array<int, 3>{5, 2, 1},
                                {1, 1, 4},
                                {7, 3, 3},
                                {64, 16, 2},
                                {1, 9, 1},
                                {33, 17, 4},
                                {100, 1, 3}}) {
    const MipPyramid p = pyramidOf(w, h, c, [](int x, int y, int k) { return x + y + k; });
    EXPECT_EQ(MipPyramid::bytesFor(w, h, c), double(p.bytes())) << w << "x" << h << "x" << c;
  }
}

TEST(MipPyramid, ATexelCentreWithoutFootprintIsThatTexel) {
  const MipPyramid p = pyramidOf(4, 4, 3, [](int x, int y, int c) { return x + 4 * y + 100 * c; });
  float rgb[3];
  p.filter({{2.5f / 4, 1.5f / 4}, {0, 0}, {0, 0}}, 0, 3, rgb);
  EXPECT_FLOAT_EQ(rgb[0], 6);  // texel (2, 1)
  EXPECT_FLOAT_EQ(rgb[1], 106);
  EXPECT_FLOAT_EQ(rgb[2], 206);
}

TEST(MipPyramid, ThreeChannelsOfEachLevelsLastTexelAreThatTexel) {
  // Three channels are read four at a time: at the last texel of a level the fourth is the
  // level's padding, never part of the result. Every value here is a sum of quarters of small
  // integers, exact in float.
  const MipPyramid p = pyramidOf(4, 4, 3, [](int x, int y, int c) { return x + 4 * y + 100 * c; });
  const auto rgbAt = [&](Vec2f st, Vec2f axis) {
    std::vector<float> rgb(3);
    p.filter({st, axis, {axis.y, axis.x}, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge}, 0, 3,
             rgb.data());
    return rgb;
  };
  // Texel (3, 3), the finest level's last, without a footprint.
  EXPECT_EQ(rgbAt({3.5f / 4, 3.5f / 4}, {0, 0}), (std::vector<float>{15, 115, 215}));
  // A footprint twice the image's width reads the 1 × 1 level: the image's mean, 7.5 + 100c.
  EXPECT_EQ(rgbAt({0.5f, 0.5f}, {2, 0}), (std::vector<float>{7.5f, 107.5f, 207.5f}));
}

TEST(MipPyramid, WrapModesContinueTheImageAsTheySay) {
  // One row of 4 texels 0, 1, 2, 3, read left of the image's edge: at s = −1/8, the centre of
  // texel −1, repeat gives texel 3, clamp texel 0, mirror texel 0 (−1 mirrors to 0); at
  // s = −1/4, between texels −2 and −1: repeat (2 + 3) / 2, clamp 0, mirror (1 + 0) / 2.
  const MipPyramid p = pyramidOf(4, 1, 1, [](int x, int, int) { return x; });
  const auto at = [&](float s, TextureWrap w) { return lookUp(p, {s, 0.5f}, {}, {}, 0, w); };
  EXPECT_FLOAT_EQ(at(-0.125f, TextureWrap::Repeat), 3);
  EXPECT_FLOAT_EQ(at(-0.125f, TextureWrap::ClampToEdge), 0);
  EXPECT_FLOAT_EQ(at(-0.125f, TextureWrap::MirroredRepeat), 0);
  EXPECT_FLOAT_EQ(at(-0.25f, TextureWrap::Repeat), 2.5f);
  EXPECT_FLOAT_EQ(at(-0.25f, TextureWrap::ClampToEdge), 0);
  EXPECT_FLOAT_EQ(at(-0.25f, TextureWrap::MirroredRepeat), 0.5f);
  // Far away: repeat has period 1, mirror period 2 (s = 1001.125 lies half a texel into a
  // mirrored period, on the centre of its first texel, which is texel 3); clamp the edge's.
  EXPECT_FLOAT_EQ(at(1000.625f, TextureWrap::Repeat), at(0.625f, TextureWrap::Repeat));
  EXPECT_FLOAT_EQ(at(1001.125f, TextureWrap::MirroredRepeat), 3);
  EXPECT_FLOAT_EQ(at(40.0f, TextureWrap::ClampToEdge), 3);
}

TEST(MipPyramid, AnyFootprintOfALinearRampGivesTheRampAtItsCentre) {
  // Box averages and bilinear interpolation of a linear function, at texel centres of a
  // power-of-two image, are that function: so every level and every blend of levels and of
  // points spread symmetrically along an axis gives f(s, t) itself, whatever the footprint,
  // up to float rounding (values ≤ 200, 1e-3). An offset of half a texel at any level would
  // show as 0.5 · 2^level · 0.3 or more.
  const int n = 256;
  const auto f = [](double x, double y) { return 0.3 * x + 0.5 * y + 7; };  // x, y in texels
  const MipPyramid p = pyramidOf(n, n, 1, [&](int x, int y, int) { return f(x + 0.5, y + 0.5); });
  // The largest footprint (48 × 6 texels) reads no further than 24 + 16 texels from its centre,
  // nowhere near the image's edges, where clamping would bend the ramp.
  for (const float scale : {0.0f, 0.5f, 1.5f, 3.0f, 6.0f})
    for (const float stretch : {1.0f, 3.0f, 8.0f})
      for (const float angle : {0.0f, 0.4f, 1.2f}) {
        // A footprint of `scale` texels across, `stretch` times longer along `angle`, centred
        // well inside the image (the ramp does not wrap).
        const float c = std::cos(angle), s = std::sin(angle);
        const Vec2f a{scale * stretch * c / n, scale * stretch * s / n};
        const Vec2f b{-scale * s / n, scale * c / n};
        const Vec2f st{0.5f + 0.03f * angle, 0.45f};
        EXPECT_NEAR(lookUp(p, st, a, b, 0, TextureWrap::ClampToEdge), f(st.x * n, st.y * n), 1e-3)
            << scale << " " << stretch << " " << angle;
      }
}

TEST(MipPyramid, TheFilterStaysWithinItsTaylorBoundOfTheImage) {
  // A smooth image f = sin(2πx/P)·sin(2πy/Q) (texels). A filter is a weighted sum of texels whose
  // weights sum to 1 and whose mean position is the lookup's centre (box averages, bilinear
  // weights and points spread symmetrically all keep it there), so by Taylor's theorem it
  // differs from f at the centre by at most ½·‖∇²f‖·E|d|², E|d|² the weights' second moment
  // about the centre. ‖∇²f‖ ≤ (2π/P)² + (2π/Q)² (the Hessian's Frobenius norm). E|d|² adds
  // up: the points' spread along the major diameter D, at most D²/12; a bilinear tap's, at
  // most T²/4 per axis for texels T finest texels wide; a box of T, T²/12 per axis. Bilinear
  // at the finest level alone (D ≤ 1): 2·¼; else level L and L + 1 (T up to 2^(L+1)):
  // D²/12 + 2·(1/4 + 1/12)·4^(L+1). The periods divide the image's size, so repeating it
  // is seamless. The filter reaches 0.4 of this bound here; read half a texel off centre it
  // reached 6.5 times it, over footprints twice as wide 1.6 times it.
  const int n = 512;
  const double P = 128, Q = 64;
  const auto f = [&](double x, double y) {
    return std::sin(2 * kPi * x / P) * std::sin(2 * kPi * y / Q);
  };
  const MipPyramid p = pyramidOf(n, n, 1, [&](int x, int y, int) { return f(x + 0.5, y + 0.5); });
  const double hessian = std::pow(2 * kPi / P, 2) + std::pow(2 * kPi / Q, 2);
  int checked = 0;
  for (const float scale : {0.5f, 1.0f, 2.0f, 4.0f, 8.0f})
    for (const float stretch : {1.0f, 2.5f, 8.0f})
      for (int k = 0; k < 8; ++k) {
        const float angle = 0.7f * float(k), c = std::cos(angle), s = std::sin(angle);
        const Vec2f a{scale * stretch * c / n, scale * stretch * s / n};
        const Vec2f b{-scale * s / n, scale * c / n};
        const Vec2f st{0.1f + 0.11f * float(k), 0.9f - 0.1f * float(k)};
        const double major = scale * stretch;
        const double minor = std::max(double(scale), major / MipPyramid::kMaxAnisotropy);
        const double level = minor > 1 ? std::floor(std::log2(minor)) : 0;
        const double moment =
            major <= 1 ? 0.5
                       : major * major / 12 + 2 * (1.0 / 4 + 1.0 / 12) * std::pow(4.0, level + 1);
        const double bound = 0.5 * hessian * moment;
        const double error = std::fabs(lookUp(p, st, a, b) - f(st.x * n, st.y * n));
        EXPECT_LE(error, bound + 1e-5) << scale << " " << stretch << " " << angle;
        ++checked;
      }
  EXPECT_EQ(checked, 120);
}

TEST(MipPyramid, AnAnisotropicFootprintIsNotBlurredAlongItsMinorAxis) {
  // Stripes 8 texels wide along x (period 16), a footprint 32 texels long along the stripes
  // (y) and 1 across: its minor axis widened to 1/8 of the major (4 texels) reads level 2,
  // whose texels under the lookup lie in the one stripe, at 8 points along y: the stripe's
  // value (≥ 0.9 allows rounding), where an isotropic filter of the major axis gives the
  // stripes' mean, 0.5.
  const int n = 256;
  const MipPyramid p = pyramidOf(n, n, 1, [](int x, int, int) { return (x / 8) % 2; });
  const float v = lookUp(p, {12.0f / n, 0.5f}, {0, 32.0f / n}, {1.0f / n, 0});
  EXPECT_GT(v, 0.9f);
  const float isotropic = lookUp(p, {12.0f / n, 0.5f}, {0, 32.0f / n}, {32.0f / n, 0});
  EXPECT_NEAR(isotropic, 0.5f, 0.05f);  // 32 texels span two periods: their mean
}

TEST(MipPyramid, NonFiniteLookupsGiveZeroOrAFiniteValue) {
  const MipPyramid p = pyramidOf(8, 8, 1, [](int, int, int) { return 0.25; });
  const float nan = std::nanf(""), inf = INFINITY;
  EXPECT_EQ(lookUp(p, {nan, 0.5f}, {}, {}), 0);
  EXPECT_EQ(lookUp(p, {0.5f, inf}, {}, {}), 0);
  // A footprint that is NaN or unbounded reads the finest or the coarsest level: still the
  // image's constant.
  EXPECT_FLOAT_EQ(lookUp(p, {0.5f, 0.5f}, {nan, 0}, {0, 0}), 0.25f);
  EXPECT_FLOAT_EQ(lookUp(p, {0.5f, 0.5f}, {inf, 0}, {0, 1e30f}), 0.25f);
  EXPECT_FLOAT_EQ(lookUp(p, {3e9f, -7e12f}, {1e-3f, 0}, {0, 1e-3f}), 0.25f);
}

}  // namespace
}  // namespace glint
