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

// Where both ShadowOrigin tests draw their points: random positions and error bounds, every
// fourth normal axis-aligned (where the offset's sign decides nothing), every third point lifted.
struct RandomPoints {
  std::mt19937 rng;
  std::uniform_real_distribution<float> coord{-20, 20}, unit{-1, 1}, err{0, 1e-4f};
  explicit RandomPoints(uint32_t seed) : rng(seed) {}
  Vec3f inCube() { return {coord(rng), coord(rng), coord(rng)}; }
  Vec3f direction() { return normalize(Vec3f{unit(rng), unit(rng), unit(rng)}); }
  ShadingPoint point(int i) {
    ShadingPoint sp;
    sp.p = inCube();
    sp.pError = {err(rng), err(rng), err(rng)};
    sp.ng = i % 4 == 0 ? Vec3f{0, 1, 0} : direction();
    sp.lifted = i % 3 == 0;
    if (sp.lifted) sp.shadowLift = 0.01f * Vec3f{unit(rng), unit(rng), unit(rng)};
    return sp;
  }
};

bool sameRay(const Ray& a, const Ray& b) {
  return sameBits(a.o, b.o) && sameBits(a.d, b.d) && a.tMin == b.tMin && a.tMax == b.tMax &&
         a.time == b.time && a.origin == b.origin;
}

TEST(ShadingPoint, ShadowOriginSpawnsSpawnShadowRayIntosRaysBitForBit) {
  // The batched kernel sets a point's shadow origin up once for all its light samples; its
  // images equal the reference integrator's only if every ray is spawnShadowRayInto's to the
  // bit: targets on both sides of the surface and in its plane, lifted points or not.
  RandomPoints random(45);
  int rays = 0, behind = 0;
  for (int i = 0; i < 2000; ++i) {
    const ShadingPoint sp = random.point(i);
    const ShadowOrigin from(sp);
    for (int j = 0; j < 8; ++j) {
      Vec3f target = random.inCube();
      if (j == 7 && i % 4 == 0) target.y = sp.p.y;  // in the plane of the unlifted point
      Ray expected, got;
      spawnShadowRayInto(expected, sp, true, target, 0.25f, 3);
      from.spawnTo(got, target, 0.25f, ray_origin::light(3));
      ASSERT_TRUE(sameRay(got, expected)) << i << " " << j;
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
  RandomPoints random(46);
  int rays = 0, behind = 0;
  for (int i = 0; i < 2000; ++i) {
    const ShadingPoint sp = random.point(i);
    const ShadowOrigin from(sp);
    for (int j = 0; j < 8; ++j) {
      Vec3f w = random.direction();
      if (j == 7 && i % 4 == 0) w = normalize(Vec3f{w.x, 0, w.z});  // in the plane
      Ray expected, got;
      spawnShadowRayInto(expected, sp, false, w, 0.75f, 2);
      from.spawnAlong(got, w, 0.75f, ray_origin::light(2));
      ASSERT_TRUE(sameRay(got, expected)) << i << " " << j;
      behind += dot(w, sp.ng) < 0;
      ++rays;
    }
  }
  EXPECT_GT(behind, rays / 4);
  EXPECT_LT(behind, 3 * rays / 4);
}

}  // namespace
}  // namespace glint
