// A point light's samples in lanes (integrator/point_light_lanes.h) against the scalar code they
// stand for: sampleLight (lights/light.h), queueSamples' test and spawnShadowRayInto
// (geometry/shading_point.h). The batched kernel's images equal the reference integrator's only
// if every lane holds the scalar bits.
#include "integrator/point_light_lanes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "lights/light.h"
#include "materials/surface.h"

namespace glint {
namespace {

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool sameBits(const Vec3f& a, const Vec3f& b) {
  return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

// Laid out as the kernel's pending points are: a surface point and, further on, its normal.
struct Point {
  ShadingPoint sp;
  SurfacePoint at;
};

// Random points around the light: every fourth geometric normal axis-aligned (offsets with zero
// components), every third point lifted, every fifth at a coordinate of 0 (where the offset
// steps to the smallest subnormal), shading normals facing the light or not.
std::vector<Point> randomPoints(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord{-20, 20}, unit{-1, 1}, err{0, 1e-4f};
  const auto direction = [&] { return normalize(Vec3f{unit(rng), unit(rng), unit(rng)}); };
  std::vector<Point> points(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    ShadingPoint& sp = points[static_cast<size_t>(i)].sp;
    sp.p = {coord(rng), coord(rng), coord(rng)};
    if (i % 5 == 0) sp.p.x = 0;
    sp.pError = {err(rng), err(rng), err(rng)};
    sp.ng = i % 4 == 0 ? Vec3f{0, 1, 0} : direction();
    sp.ns = sp.ng;
    sp.lifted = i % 3 == 0;
    if (sp.lifted) sp.shadowLift = 0.01f * Vec3f{unit(rng), unit(rng), unit(rng)};
    points[static_cast<size_t>(i)].at.n = direction();
  }
  return points;
}

void expectScalarBits(const PointLight& light, const std::vector<Point>& points) {
  const int n = static_cast<int>(points.size());
  PointLightLanes lanes;
  samplePointLight(light.position, light.intensity, light.falloff == Falloff::InverseSquare,
                   &points[0].sp, &points[0].at.n, sizeof(Point), n, lanes);
  int contributing = 0;
  for (int k = 0; k < n; ++k) {
    const Point& pt = points[static_cast<size_t>(k)];
    const LightSample ls = sampleLight(light, pt.sp.p, pt.at.n, {0.5f, 0.5f});
    const bool contributes = facesLight(pt.at, ls.wi) && !ls.intensity.isBlack();
    ASSERT_EQ(lanes.contributes[k] != 0, contributes) << k;
    contributing += contributes;
    EXPECT_TRUE(sameBits({lanes.wi[0][k], lanes.wi[1][k], lanes.wi[2][k]}, ls.wi)) << k;
    EXPECT_TRUE(sameBits(lanes.intensity[0][k], ls.intensity.r) &&
                sameBits(lanes.intensity[1][k], ls.intensity.g) &&
                sameBits(lanes.intensity[2][k], ls.intensity.b))
        << k;
    const Ray expected = spawnShadowRay(pt.sp, true, ls.target, 0, 0);
    EXPECT_TRUE(sameBits({lanes.o[0][k], lanes.o[1][k], lanes.o[2][k]}, expected.o)) << k;
    EXPECT_TRUE(sameBits({lanes.d[0][k], lanes.d[1][k], lanes.d[2][k]}, expected.d)) << k;
  }
  // Both answers of the test were exercised (the normals face the light about half the time).
  EXPECT_GT(contributing, n / 4);
  EXPECT_LT(contributing, 3 * n / 4);
}

TEST(PointLightLanes, HoldTheScalarSamplesAndShadowRaysBitForBit) {
  // 61 points: seven whole blocks of eight lanes and a partial one.
  const std::vector<Point> points = randomPoints(61, 47);
  expectScalarBits(PointLight{{1.5f, 5, 1.5f}, {0.8f, 0.7f, 0.6f}, Falloff::InverseSquare}, points);
  expectScalarBits(PointLight{{-3, 2.5f, -2}, {0.3f, 0.32f, 0.4f}, Falloff::None}, points);
}

TEST(PointLightLanes, ABlackLightContributesNothing) {
  // No sample of a light without intensity is queued, wherever the point faces.
  const std::vector<Point> points = randomPoints(9, 3);
  PointLightLanes lanes;
  samplePointLight({0, 10, 0}, {0, 0, 0}, true, &points[0].sp, &points[0].at.n, sizeof(Point), 9,
                   lanes);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(lanes.contributes[k], 0) << k;
}

}  // namespace
}  // namespace glint
