// Shadow rays spawned from a point (geometry/shading_point.h).
#include "geometry/shading_point.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

namespace glint {
namespace {

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool sameBits(const Vec3f& a, const Vec3f& b) {
  return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

TEST(ShadingPoint, ShadowOriginSpawnsSpawnShadowRayIntosRaysBitForBit) {
  // The batched kernel sets a point's shadow origin up once for all its light samples; its
  // images equal the reference integrator's only if every ray is spawnShadowRayInto's to the
  // bit: targets on both sides of the surface and in its plane, lifted points or not, normals
  // with zero coordinates (where the offset's sign decides nothing).
  std::mt19937 rng(45);
  std::uniform_real_distribution<float> coord(-20, 20), unit(-1, 1), err(0, 1e-4f);
  int rays = 0, behind = 0;
  for (int i = 0; i < 2000; ++i) {
    ShadingPoint sp;
    sp.p = {coord(rng), coord(rng), coord(rng)};
    sp.pError = {err(rng), err(rng), err(rng)};
    sp.ng = i % 4 == 0 ? Vec3f{0, 1, 0} : normalize(Vec3f{unit(rng), unit(rng), unit(rng)});
    sp.lifted = i % 3 == 0;
    if (sp.lifted) sp.shadowLift = 0.01f * Vec3f{unit(rng), unit(rng), unit(rng)};
    const ShadowOrigin from(sp);
    for (int j = 0; j < 8; ++j) {
      Vec3f target = {coord(rng), coord(rng), coord(rng)};
      if (j == 7 && i % 4 == 0) target.y = sp.p.y;  // in the plane of the unlifted point
      Ray expected, got;
      spawnShadowRayInto(expected, sp, true, target, 0.25f, 3);
      from.spawnTo(got, target, 0.25f, ray_origin::light(3));
      ASSERT_TRUE(sameBits(got.o, expected.o)) << i << " " << j;
      ASSERT_TRUE(sameBits(got.d, expected.d)) << i << " " << j;
      EXPECT_EQ(got.tMin, expected.tMin);
      EXPECT_EQ(got.tMax, expected.tMax);
      EXPECT_EQ(got.time, expected.time);
      EXPECT_EQ(got.origin, expected.origin);
      behind += dot(target - sp.p, sp.ng) < 0;
      ++rays;
    }
  }
  // Both sides were exercised (about half the targets each).
  EXPECT_GT(behind, rays / 4);
  EXPECT_LT(behind, 3 * rays / 4);
}

TEST(ShadingPoint, ShadowOriginSpawnsRaysToInfinityAsSpawnShadowRayIntoBitForBit) {
  // The environment's many samples per point leave through spawnAlong; the reference
  // integrator's through spawnShadowRayInto without a target point. Directions on both sides,
  // in the plane, lifted points or not.
  std::mt19937 rng(46);
  std::uniform_real_distribution<float> coord(-20, 20), unit(-1, 1), err(0, 1e-4f);
  int rays = 0, behind = 0;
  for (int i = 0; i < 2000; ++i) {
    ShadingPoint sp;
    sp.p = {coord(rng), coord(rng), coord(rng)};
    sp.pError = {err(rng), err(rng), err(rng)};
    sp.ng = i % 4 == 0 ? Vec3f{0, 1, 0} : normalize(Vec3f{unit(rng), unit(rng), unit(rng)});
    sp.lifted = i % 3 == 0;
    if (sp.lifted) sp.shadowLift = 0.01f * Vec3f{unit(rng), unit(rng), unit(rng)};
    const ShadowOrigin from(sp);
    for (int j = 0; j < 8; ++j) {
      Vec3f w = normalize(Vec3f{unit(rng), unit(rng), unit(rng)});
      if (j == 7 && i % 4 == 0) w = normalize(Vec3f{w.x, 0, w.z});  // in the plane
      Ray expected, got;
      spawnShadowRayInto(expected, sp, false, w, 0.75f, 2);
      from.spawnAlong(got, w, 0.75f, ray_origin::light(2));
      ASSERT_TRUE(sameBits(got.o, expected.o)) << i << " " << j;
      ASSERT_TRUE(sameBits(got.d, expected.d)) << i << " " << j;
      EXPECT_EQ(got.tMin, expected.tMin);
      EXPECT_EQ(got.tMax, expected.tMax);
      EXPECT_EQ(got.time, expected.time);
      EXPECT_EQ(got.origin, expected.origin);
      behind += dot(w, sp.ng) < 0;
      ++rays;
    }
  }
  EXPECT_GT(behind, rays / 4);
  EXPECT_LT(behind, 3 * rays / 4);
}

}  // namespace
}  // namespace glint
