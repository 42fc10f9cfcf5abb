// Textures on their own (materials/texture.h, procedural.h, image_texture.h): the solid
// patterns against their defining properties, and the pixel footprint carried into (u, v).
#include "materials/texture.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/hash.h"
#include "materials/procedural.h"

namespace glint {
namespace {

TEST(Procedural, PerlinNoiseVanishesOnTheLatticeAndStaysInRange) {
  // Perlin's gradient noise is zero at every integer point (each corner's gradient is dotted
  // with a zero offset there) and within [-1, 1] everywhere.
  for (int x = -3; x <= 3; ++x)
    for (int z = -3; z <= 3; ++z) EXPECT_EQ(perlinNoise({double(x), 7, double(z)}), 0.0f);
  float lo = 1, hi = -1;
  for (int i = 0; i < 20000; ++i) {
    const double t = i * 0.0137;
    const float n = perlinNoise({t, std::sin(t) * 3.1, t * 0.37 - 4});
    lo = std::min(lo, n), hi = std::max(hi, n);
  }
  EXPECT_GE(lo, -1.0f);
  EXPECT_LE(hi, 1.0f);
  // And it varies: over 20000 points spread across ~270 cells it reaches well past ±0.3
  // (a constant or broken hash would not).
  EXPECT_LT(lo, -0.3f);
  EXPECT_GT(hi, 0.3f);
}

TEST(Procedural, PerlinNoiseIsContinuousAcrossCellFaces) {
  // Either side of a lattice face, 1e-9 apart, the noise differs by at most its slope times
  // that step (the gradient is bounded: |∇n| < 4 with these gradients and fades).
  for (double y = 0.05; y < 1; y += 0.1) {
    const float below = perlinNoise({2 - 1e-9, y, 0.3}), above = perlinNoise({2 + 1e-9, y, 0.3});
    EXPECT_NEAR(below, above, 1e-7);
  }
}

TEST(Procedural, PerlinNoiseDoesNotDependOnTheCellsRememberedBefore) {
  // Each thread remembers recent cells' gradients (a pure function's results): a point's noise
  // is the same bits when its cell is remembered, after another cell has replaced it, after
  // thousands of others, and with a NaN clamped as fmax(-1, fmin(1, NaN)) clamps it, to 1.
  const Vec3d p{0.3, 12.7, -5.2};
  const float first = perlinNoise(p), again = perlinNoise(p);
  EXPECT_EQ(again, first);
  // Cells 4096 apart in x take the same place in a cache of up to 4096 (a power of two): each
  // of these replaces p's cell.
  for (int k = 1; k <= 8; ++k) {
    perlinNoise({p.x + 4096.0 * k, p.y, p.z});
    EXPECT_EQ(perlinNoise(p), first) << k;
  }
  for (int i = 0; i < 5000; ++i) perlinNoise({i * 1.37, i * -0.71, i * 2.03});
  EXPECT_EQ(perlinNoise(p), first);
  EXPECT_EQ(perlinNoise({std::nan(""), 0.5, 0.5}), 1.0f);
}

// Perlin's improved noise as the scalar formula writes it, one corner and one interpolation at
// a time: what perlinNoise's lanes must reproduce bit for bit.
float scalarPerlinNoise(const Vec3d& p) {
  const auto floorOf = [](double x) { return static_cast<long long>(std::floor(x)); };
  const long long ix = floorOf(p.x), iy = floorOf(p.y), iz = floorOf(p.z);
  const double x = p.x - double(ix), y = p.y - double(iy), z = p.z - double(iz);
  const auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const auto lerp = [](double t, double a, double b) { return a + t * (b - a); };
  const double u = fade(x), v = fade(y), w = fade(z);
  const auto g = [&](int dx, int dy, int dz) {
    const uint64_t h =
        hashCombine(hashCombine(hashKey(uint64_t(ix + dx)), uint64_t(iy + dy)), uint64_t(iz + dz));
    const double a = x - dx, b = y - dy, c = z - dz;
    // The twelve edge directions ±a ± b (a - b is a + (-b), exactly).
    const double terms[12][2] = {{a, b},  {-a, b},  {a, -b}, {-a, -b}, {a, c},  {-a, c},
                                 {a, -c}, {-a, -c}, {b, c},  {-b, c},  {b, -c}, {-b, -c}};
    return terms[h % 12][0] + terms[h % 12][1];
  };
  const double n =
      lerp(w, lerp(v, lerp(u, g(0, 0, 0), g(1, 0, 0)), lerp(u, g(0, 1, 0), g(1, 1, 0))),
           lerp(v, lerp(u, g(0, 0, 1), g(1, 0, 1)), lerp(u, g(0, 1, 1), g(1, 1, 1))));
  return float(std::fmax(-1.0, std::fmin(1.0, n)));
}

TEST(Procedural, PerlinNoiseInLanesIsTheScalarFormula) {
  // The lanes do each corner's and each interpolation's operations as the formula does, so the
  // noise is the same bits (compared as bits: an exact zero keeps its sign too), in cells on
  // both sides of zero, far from the origin, and at cells remembered or not.
  for (int i = 0; i < 20000; ++i) {
    const double t = i * 0.0173;
    const Vec3d p{t * 1.3 - 90, std::sin(t) * 7.7, std::cos(t * 0.7) * 3e5 + i % 7};
    EXPECT_EQ(std::bit_cast<uint32_t>(perlinNoise(p)),
              std::bit_cast<uint32_t>(scalarPerlinNoise(p)))
        << p.x << " " << p.y << " " << p.z;
  }
}

TEST(Procedural, PatternsAreBlendWeightsInTheUnitInterval) {
  for (int i = 0; i < 5000; ++i) {
    const Vec3d p{i * 0.031, i * 0.017 - 20, std::cos(i * 0.1) * 5};
    for (float w : {noisePattern(p), marblePattern(p), woodPattern(p), checkerPattern(p)}) {
      EXPECT_GE(w, 0.0f);
      EXPECT_LE(w, 1.0f);
    }
  }
  // The checker alternates by cell: (0.5, 0.5, 0.5) is cell sum 0, one cell over is sum 1.
  EXPECT_EQ(checkerPattern({0.5, 0.5, 0.5}), 0.0f);
  EXPECT_EQ(checkerPattern({1.5, 0.5, 0.5}), 1.0f);
  // Wood's rings: on the y axis (radius 0) only turbulence moves the phase, which is ≥ 0 and
  // small near the lattice point at the origin.
  EXPECT_LT(woodPattern({0, 0, 0}), 1e-6f);
}

TEST(ColorTexture, SolidPatternsBlendTheirTwoColoursInWorldSpace) {
  ColorTexture t;
  t.pattern = TexturePattern::Checker;
  t.a = {1, 0, 0};
  t.b = {0, 0, 1};
  t.scale = 2;
  ShadingPoint sp;
  sp.p = {0.5f, 0.5f, 0.5f};  // render space; the world origin moves it by 2 in x
  const Vec3f wo{0, 0, 1};
  // World point (2.5, 0.5, 0.5), scale 2 → (1.25, 0.25, 0.25): cell sum 1 → b.
  EXPECT_EQ(t.eval({sp, wo, 0, Vec3d{2, 0, 0}}), (Rgb{0, 0, 1}));
  EXPECT_EQ(t.eval({sp, wo, 0, Vec3d{}}), (Rgb{1, 0, 0}));
  EXPECT_FALSE(t.isBlack());
}

// A surface in the x–y plane facing +z whose (u, v) runs 0.5 per unit in x and in y.
ShadingPoint planeWithTangents() {
  ShadingPoint sp;
  sp.ng = sp.ns = {0, 0, 1};
  sp.uv = {0.25f, 0.75f};
  sp.dpdu = {2, 0, 0};
  sp.dpdv = {0, 2, 0};
  return sp;
}

TEST(ImageFootprint, HeadOnAFootprintOfWidthWCoversWOverTheTangentLength) {
  const ShadingPoint sp = planeWithTangents();
  const ImageFootprint f = imageFootprint(sp, {0, 0, 1}, 0.1f, {});
  // t = 1 − v: images count rows from the top.
  EXPECT_FLOAT_EQ(f.st.x, 0.25f);
  EXPECT_FLOAT_EQ(f.st.y, 0.25f);
  // 0.1 world units across is 0.05 in (u, v) along either axis, and the two axes are
  // perpendicular.
  EXPECT_NEAR(std::hypot(f.axisA.x, f.axisA.y), 0.05f, 1e-7);
  EXPECT_NEAR(std::hypot(f.axisB.x, f.axisB.y), 0.05f, 1e-7);
  EXPECT_NEAR(f.axisA.x * f.axisB.x + f.axisA.y * f.axisB.y, 0.0f, 1e-9);
}

TEST(ImageFootprint, ObliqueViewsStretchTheFootprintAlongTheRay) {
  const ShadingPoint sp = planeWithTangents();
  // Seen from 60° off the normal, in the x–z plane: along x (u) the footprint is 1/cos 60° = 2
  // times longer; across (y, v) it keeps its width.
  const float a = 60 * kPi / 180;
  const ImageFootprint f = imageFootprint(sp, {std::sin(a), 0, std::cos(a)}, 0.1f, {});
  EXPECT_NEAR(std::fabs(f.axisA.y), 0.05f, 1e-7);  // across: along v
  EXPECT_NEAR(f.axisA.x, 0.0f, 1e-7);
  EXPECT_NEAR(std::fabs(f.axisB.x), 0.1f, 1e-6);  // along: 0.05 / cos 60°
  EXPECT_NEAR(f.axisB.y, 0.0f, 1e-7);
}

TEST(ImageFootprint, TheUvTransformMovesThePointAndScalesTheAxes) {
  const ShadingPoint sp = planeWithTangents();
  // Scale u by 4 and offset by (0.5, 0): u = 0.25 → 1.5; the footprint along u is 4× longer.
  const UvTransform t = UvTransform::offsetRotateScale({0.5f, 0}, 0, {4, 1});
  const ImageFootprint f = imageFootprint(sp, {0, 0, 1}, 0.1f, t);
  EXPECT_FLOAT_EQ(f.st.x, 1.5f);
  EXPECT_FLOAT_EQ(f.st.y, 0.25f);
  const float lengthA = std::hypot(f.axisA.x, f.axisA.y),
              lengthB = std::hypot(f.axisB.x, f.axisB.y);
  EXPECT_NEAR(std::max(lengthA, lengthB), 0.2f, 1e-6);
  EXPECT_NEAR(std::min(lengthA, lengthB), 0.05f, 1e-6);
}

TEST(ImageFootprint, WithoutTangentsTheImageIsReadAtAPoint) {
  ShadingPoint sp = planeWithTangents();
  sp.dpdu = sp.dpdv = {};
  const ImageFootprint f = imageFootprint(sp, {0, 0, 1}, 0.1f, {});
  EXPECT_EQ(f.axisA.x, 0.0f);
  EXPECT_EQ(f.axisB.y, 0.0f);
}

}  // namespace
}  // namespace glint
