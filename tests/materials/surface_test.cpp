// The general surface of seed 002 §9.1 (materials/surface.h) on its own, at given normals and
// directions: Lambert, the Blinn-Phong and Phong highlights, ambient light, emission and the
// mirror direction, each against its closed form.
#include "materials/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glint {
namespace {

// A point at the origin on a surface facing +y, with `ns` as shading normal.
ShadingPoint pointFacing(Vec3f ns = {0, 1, 0}) {
  ShadingPoint sp;
  sp.ng = {0, 1, 0};
  sp.ns = ns;
  return sp;
}

Surface glossyPaint(SpecularModel model) {
  Surface s;
  s.kd = ColorTexture::uniform({0.2f, 0.2f, 0.2f});
  s.ks = ColorTexture::uniform({0.5f, 0.5f, 0.5f});
  s.exponent = 10;
  s.specularModel = model;
  return s;
}

Vec3f at(float degrees) {  // unit, in the x–y plane, `degrees` from +y towards +x
  const float a = degrees * kPi / 180;
  return {std::sin(a), std::cos(a), 0};
}

TEST(Surface, SpecularPowerMatchesPowWithinItsRoundingBound) {
  // Whole exponents go by repeated squaring: each squaring doubles the relative error it is
  // given, so the bound is (2·exponent + 2) float roundings (2^-24 each) of the exact power;
  // below float's smallest normal number (where renders flush to zero) absolutely.
  for (float e : {0.0f, 1.0f, 2.0f, 5.0f, 30.0f, 32.0f, 100.0f, 1000.0f, 65535.0f})
    for (float c = 0; c <= 1; c += 1.0f / 64) {
      const double exact = std::pow(double(c), double(e));
      const double bound =
          (2 * double(e) + 2) * std::ldexp(1.0, -24) * exact + std::numeric_limits<float>::min();
      EXPECT_NEAR(specularPower(c, e), exact, bound) << c << "^" << e;
    }
  EXPECT_EQ(specularPower(0, 0), 1.0f);  // as powf: 0^0 = 1
  EXPECT_EQ(specularPower(1, 65535), 1.0f);
  // Fractional and very large exponents are powf's.
  EXPECT_EQ(specularPower(0.7f, 12.5f), std::pow(0.7f, 12.5f));
  EXPECT_EQ(specularPower(0.999f, 1e6f), std::pow(0.999f, 1e6f));
}

TEST(Surface, LambertIsKdTimesTheCosine) {
  Surface s;
  s.kd = ColorTexture::uniform({0.6f, 0.3f, 0.1f});
  const SurfacePoint p = lookUp(s, pointFacing(), at(10), 0, {});
  // Light at 60° from the normal: k_d·cos 60° = k_d / 2.
  const Rgb f = reflectedLight(s, pointFacing(), p, at(-60));
  EXPECT_NEAR(f.r, 0.3f, 1e-7);
  EXPECT_NEAR(f.g, 0.15f, 1e-7);
  EXPECT_NEAR(f.b, 0.05f, 1e-7);
}

TEST(Surface, BlinnPhongPeakAndAngle) {
  const Surface s = glossyPaint(SpecularModel::BlinnPhong);
  // Light at 45° on one side, viewer at 45° on the other: h = n, so f = k_d cos 45° + k_s.
  EXPECT_NEAR(reflectedLight(s, pointFacing(), lookUp(s, pointFacing(), at(45), 0, {}), at(-45)).r,
              0.2f * std::sqrt(0.5f) + 0.5f, 1e-6);
  // Viewer at 60°: h sits at (60° − 45°)/2 = 7.5° from n → k_s·cos(7.5°)^10.
  EXPECT_NEAR(reflectedLight(s, pointFacing(), lookUp(s, pointFacing(), at(60), 0, {}), at(-45)).r,
              0.2f * std::sqrt(0.5f) + 0.5f * std::pow(std::cos(7.5f * kPi / 180), 10.0f), 1e-6);
}

TEST(Surface, PhongPeakAndAngle) {
  // Phong uses r·v, r the mirror image of the light direction (45°): 15° off at a 60° viewer.
  const Surface s = glossyPaint(SpecularModel::Phong);
  EXPECT_NEAR(reflectedLight(s, pointFacing(), lookUp(s, pointFacing(), at(45), 0, {}), at(-45)).r,
              0.2f * std::sqrt(0.5f) + 0.5f, 1e-6);
  EXPECT_NEAR(reflectedLight(s, pointFacing(), lookUp(s, pointFacing(), at(60), 0, {}), at(-45)).r,
              0.2f * std::sqrt(0.5f) + 0.5f * std::pow(std::cos(15 * kPi / 180), 10.0f), 1e-6);
}

TEST(Surface, NoLightFromBehindAndTwoSidedNormals) {
  const Surface s = glossyPaint(SpecularModel::BlinnPhong);
  // A light below the surface adds nothing, highlight included.
  EXPECT_TRUE(
      reflectedLight(s, pointFacing(), lookUp(s, pointFacing(), at(0), 0, {}), at(120)).isBlack());
  // Seen from below, the shading normal turns to the viewer and a light below lights it.
  const SurfacePoint below = lookUp(s, pointFacing(), at(180), 0, {});
  EXPECT_EQ(below.n, (Vec3f{0, -1, 0}));
  EXPECT_NEAR(reflectedLight(s, pointFacing(), below, at(180)).r, 0.2f + 0.5f, 1e-6);
}

TEST(Surface, AmbientAndEmission) {
  Surface s;
  s.kd = ColorTexture::uniform({0.5f, 0.5f, 0.5f});
  s.ka = ColorTexture::uniform({0.2f, 0.4f, 0.8f});
  s.ke = ColorTexture::uniform({1, 2, 3});
  const ShadingPoint sp = pointFacing();
  // k_a·I_a + k_e, from either side when the emission is two-sided.
  for (float view : {0.0f, 180.0f}) {
    const Rgb c = ambientAndEmission(s, lookUp(s, sp, at(view), 0, {}), sp, {0.5f, 0.5f, 0.5f}, {});
    EXPECT_NEAR(c.r, 1.1f, 1e-6) << view;
    EXPECT_NEAR(c.g, 2.2f, 1e-6) << view;
    EXPECT_NEAR(c.b, 3.4f, 1e-6) << view;
  }
  // A one-sided emitter shows k_e only on its geometric normal's side.
  s.emissionSides = EmissionSides::Front;
  EXPECT_EQ(ambientAndEmission(s, lookUp(s, sp, at(30), 0, {}), sp, {}, {}), (Rgb{1, 2, 3}));
  EXPECT_EQ(ambientAndEmission(s, lookUp(s, sp, at(150), 0, {}), sp, {}, {}), (Rgb{}));
  // k_a following k_d reads the diffuse colour looked up at the point.
  s.ambientFollowsDiffuse = true;
  s.ke = {};
  EXPECT_EQ(ambientAndEmission(s, lookUp(s, sp, at(0), 0, {}), sp, {1, 1, 1}, {}),
            (Rgb{0.5f, 0.5f, 0.5f}));
}

TEST(Surface, MirrorDirectionAndGloss) {
  // r = d − 2(d·n)n: a ray down at 30° leaves up at 30° on the other side.
  const Vec3f d = -at(-30), n{0, 1, 0};
  Vec3f r;
  ASSERT_TRUE(mirrorDirection(d, n, 0, GlossShape::Square, {}, r));
  EXPECT_NEAR(r.x, at(30).x, 1e-7);
  EXPECT_NEAR(r.y, at(30).y, 1e-7);
  // A glossy ray stays within the square of width a around r: its offset from r, in r's
  // tangent plane, is at most a/√2 before normalising (u at a corner of [0, 1)²).
  const float a = 0.2f;
  for (Vec2f u : {Vec2f{0, 0}, Vec2f{0.999f, 0.999f}, Vec2f{0.5f, 0.5f}, Vec2f{0.1f, 0.8f}}) {
    ASSERT_TRUE(mirrorDirection(d, n, a, GlossShape::Square, u, r));
    EXPECT_NEAR(length(r), 1, 1e-6);
    EXPECT_GE(dot(r, at(30)), 1 / std::sqrt(1 + a * a / 2) - 1e-6);
  }
  // The square's centre is the mirror direction itself.
  ASSERT_TRUE(mirrorDirection(d, n, a, GlossShape::Square, {0.5f, 0.5f}, r));
  EXPECT_NEAR(dot(r, at(30)), 1, 1e-6);
  // A grazing ray perturbed by a wide square ends up below the surface: no ray.
  const Vec3f grazing = normalize(Vec3f{1, -0.01f, 0});
  int below = 0;
  for (float ux = 0; ux < 1; ux += 0.125f)
    for (float uy = 0; uy < 1; uy += 0.125f)
      below += !mirrorDirection(grazing, n, 1, GlossShape::Square, {ux, uy}, r);
  EXPECT_GT(below, 0);
}

TEST(Surface, PhongLobeDrawsByTheLobesDistribution) {
  // Seed 002 §9.3's lobe (n + 1)/(2π)·cosⁿ α about r: cos α = u₁^(1/(n+1)) (the inverse of
  // P(cos α ≤ c) = c^(n+1)) and φ = 2π·u₂ about r in its tangent frame.
  const Vec3f r = normalize(Vec3f{1, 2, 3});
  Vec3f e1, e2;
  orthonormalBasis(r, e1, e2);
  for (const float n : {0.0f, 1.0f, 20.0f, 1000.0f}) {
    const Vec3f s = samplePhongLobe(r, n, {0.3f, 0.7f});
    EXPECT_NEAR(length(s), 1, 1e-6) << n;
    EXPECT_NEAR(dot(s, r), std::pow(0.3, 1 / (n + 1.0)), 1e-6) << n;
    EXPECT_NEAR(std::atan2(dot(s, e2), dot(s, e1)), 2 * kPi * 0.7 - 2 * kPi, 1e-5) << n;
  }
  // The mean of cos α over the lobe is ∫ μ·(n + 1)μⁿ dμ = (n + 1)/(n + 2): the midpoint rule
  // over u₁ (10⁴ points) reaches it to ~10⁻⁶.
  for (const float n : {0.0f, 5.0f, 50.0f}) {
    double mean = 0;
    for (int i = 0; i < 10000; ++i)
      mean += dot(samplePhongLobe(r, n, {(float(i) + 0.5f) / 10000, 0.25f}), r) / 10000;
    EXPECT_NEAR(mean, (n + 1) / (n + 2), 1e-5) << n;
  }
  // As gloss: spreads() for every exponent, n = 0 included; a lobe about the normal never
  // leaves below the surface, one about a grazing mirror direction loses about half its rays.
  EXPECT_TRUE(spreads(GlossShape::Phong, 0));
  EXPECT_FALSE(spreads(GlossShape::Square, 0));
  const Vec3f n{0, 1, 0};
  Vec3f out;
  int below = 0;
  for (float ux = 0.0625f; ux < 1; ux += 0.125f)
    for (float uy = 0.0625f; uy < 1; uy += 0.125f) {
      EXPECT_TRUE(mirrorDirection(-n, n, 10, GlossShape::Phong, {ux, uy}, out));
      below +=
          !mirrorDirection(normalize(Vec3f{1, -1e-4f, 0}), n, 10, GlossShape::Phong, {ux, uy}, out);
    }
  EXPECT_NEAR(below, 32, 4);
}

}  // namespace
}  // namespace glint
