// Intersections through every backend, against the closed forms of seed 000 §4 exercises.
#include <gtest/gtest.h>

#include <algorithm>

#include "accel/accelerator.h"
#include "test_util.h"

namespace glint {
namespace {

class Backends : public ::testing::TestWithParam<AccelKind> {
 protected:
  Hit cast(const Scene& s, Vec3f o, Vec3f d) {
    accel_ = makeAccelerator(GetParam(), s);
    Ray r;
    r.o = o;
    r.d = d;
    return accel_->intersect(r);
  }
  std::unique_ptr<Accelerator> accel_;
};

// The eye sits at the world origin, so render space (world − eye, io/placement.h) is world
// space and the rays below are written in world coordinates.
Scene oneObject(const std::string& obj) {
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
      "materials": {"m": {"type": "phong"}}, "objects": [)" +
                             obj + "]}");
}

TEST_P(Backends, SeedExerciseUnitSphere) {
  // (1,1,1) + t(−1,−1,−1) meets the unit sphere where |(1−t)(1,1,1)| = 1: t = 1 − 1/√3.
  const Scene s =
      oneObject(R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"})");
  const Hit h = cast(s, {1, 1, 1}, {-1, -1, -1});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h.t, 1 - 1 / std::sqrt(3.0), 1e-6);
  const ShadingPoint sp = s.shadingPoint({{1, 1, 1}, {-1, -1, -1}}, h);
  const float c = 1 / std::sqrt(3.0f);  // the normal points back along the ray
  EXPECT_NEAR(sp.ng.x, c, 1e-6);
  EXPECT_NEAR(length(sp.p), 1, 2.4e-7);  // re-projected onto the sphere: within 2 ulps of 1
}

TEST_P(Backends, SeedExerciseTriangle) {
  // The plane x + y + z = 1 is met at (1/3,1/3,1/3): t = 2/3, barycentrics u = v = 1/3.
  const Scene s =
      oneObject(R"({"type": "triangle", "vertices": [[1,0,0],[0,1,0],[0,0,1]], "material": "m"})");
  const Hit h = cast(s, {1, 1, 1}, {-1, -1, -1});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h.t, 2.0 / 3.0, 1e-6);
  EXPECT_NEAR(h.u, 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(h.v, 1.0 / 3.0, 1e-6);
  EXPECT_EQ(h.primId, 0u);
}

TEST_P(Backends, PlaneQuadBoxAndPolygon) {
  const Scene s = oneObject(R"(
      {"type": "plane", "point": [0,-2,0], "normal": [0,1,0], "material": "m"},
      {"type": "quad", "corner": [-1,-1,3], "edge1": [4,0,0], "edge2": [0,2,0], "material": "m"},
      {"type": "box", "min": [5,-1,-1], "max": [6,1,1], "material": "m"},
      {"type": "polygon", "vertices": [[-10,-1,-5],[-8,-1,-5],[-8,0,-5],[-9,0,-5],[-9,1,-5],[-10,1,-5]], "material": "m"})");
  // Straight down from y = 10 onto the plane y = −2: t = 12.
  Hit h = cast(s, {20, 10, 20}, {0, -1, 0});
  ASSERT_TRUE(h);
  EXPECT_EQ(h.geomId, 0u);
  EXPECT_FLOAT_EQ(h.t, 12);
  // Into the quad at (0, 0, 3) from z = 10: t = 7; (u, v) = ((0+1)/4, (0+1)/2).
  h = cast(s, {0, 0, 10}, {0, 0, -1});
  EXPECT_EQ(h.geomId, 1u);
  EXPECT_FLOAT_EQ(h.t, 7);
  EXPECT_FLOAT_EQ(h.u, 0.25f);
  EXPECT_FLOAT_EQ(h.v, 0.5f);
  // The box's −x face at x = 5 from x = 0: t = 5.
  h = cast(s, {0, 0.3f, 0.2f}, {1, 0, 0});
  EXPECT_EQ(h.geomId, 2u);
  EXPECT_FLOAT_EQ(h.t, 5);
  // The L-shaped polygon: its notch at (−8.5, 0.5) is empty, so the ray falls to the plane.
  h = cast(s, {-9.5f, 0.5f, 0}, {0, 0, -1});
  EXPECT_EQ(h.geomId, 3u);
  h = cast(s, {-8.5f, 0.5f, 0}, {0, 0, -1});
  EXPECT_FALSE(h);
}

TEST_P(Backends, InstanceTransformsPointsAndNormals) {
  // A unit sphere scaled ×2 in x: the ellipsoid x²/4 + y² + z² = 1. From (1, 0.5, 5) down −z
  // it is met at z = √(1 − 1/4 − 1/4) = √0.5, normal ∝ (x/4, y, z) by the inverse transpose.
  const Scene s = oneObject(R"({"type": "sphere", "center": [0,0,0], "radius": 1,
      "material": "m", "transform": {"scale": [2,1,1]}})");
  const Ray r{{1, 0.5f, 5}, {0, 0, -1}};
  const Hit h = cast(s, r.o, r.d);
  ASSERT_TRUE(h);
  EXPECT_EQ(h.instId, 0u);
  EXPECT_NEAR(h.t, 5 - std::sqrt(0.5), 1e-5);
  const ShadingPoint sp = s.shadingPoint(r, h);
  const Vec3f expected = normalize(Vec3f{0.25f, 0.5f, std::sqrt(0.5f)});
  EXPECT_NEAR(sp.ng.x, expected.x, 1e-5);
  EXPECT_NEAR(sp.ng.y, expected.y, 1e-5);
  EXPECT_NEAR(sp.ng.z, expected.z, 1e-5);
  EXPECT_NEAR(sp.p.z, std::sqrt(0.5), 1e-6);
}

TEST_P(Backends, OcclusionRespectsTheSegment) {
  const Scene s =
      oneObject(R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"})");
  accel_ = makeAccelerator(GetParam(), s);
  Ray r{{0, 0, 5}, {0, 0, -1}};
  r.tMax = 3.9f;  // stops 0.1 before the sphere
  EXPECT_FALSE(accel_->occluded(r));
  r.tMax = 4.1f;
  EXPECT_TRUE(accel_->occluded(r));
}

// Seed 000 §4's exercise 1 has two roots, t = 1 ∓ 1/√3: every backend, Glint's own structures
// included, finds the near one from the ray's start and the far one from past it.
class EveryBackend : public Backends {};

TEST_P(EveryBackend, SeedExerciseUnitSphereBothRoots) {
  const Scene s =
      oneObject(R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"})");
  accel_ = makeAccelerator(GetParam(), s);
  const double third = 1 / std::sqrt(3.0);
  const float c = static_cast<float>(third);
  // tMin 0: the near root, where the outward normal (1,1,1)/√3 faces back along the ray; tMin
  // 1 (the centre, past the near root): the far root, at p = −(1,1,1)/√3, the outward normal
  // −(1,1,1)/√3 along the ray.
  struct Root {
    float tMin;
    double t;
    float side;
  };
  for (const auto& [tMin, root, side] : {Root{0, 1 - third, 1}, Root{1, 1 + third, -1}}) {
    Ray r;
    r.o = {1, 1, 1};
    r.d = {-1, -1, -1};
    r.tMin = tMin;
    const Hit h = accel_->intersect(r);
    ASSERT_TRUE(h) << tMin;
    EXPECT_NEAR(h.t, root, 1e-6) << tMin;
    const ShadingPoint sp = s.shadingPoint(r, h);
    for (float n : {sp.ng.x, sp.ng.y, sp.ng.z}) EXPECT_NEAR(n, side * c, 1e-6) << tMin;
    EXPECT_NEAR(sp.p.x, side * c, 2.4e-7) << tMin;
    EXPECT_NEAR(length(sp.p), 1, 2.4e-7) << tMin;  // re-projected: within 2 ulps of 1
  }
}

INSTANTIATE_TEST_SUITE_P(All, EveryBackend,
                         ::testing::Values(AccelKind::Embree, AccelKind::Bvh, AccelKind::BruteForce,
                                           AccelKind::Grid, AccelKind::Octree, AccelKind::KdTree,
                                           AccelKind::OctreeGenerateAndTest, AccelKind::RayClass,
                                           AccelKind::Coherence, AccelKind::Spheres),
                         [](const auto& p) {
                           // A test name is letters, digits and underscores.
                           std::string name(accelName(p.param));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

INSTANTIATE_TEST_SUITE_P(All, Backends,
                         ::testing::Values(AccelKind::Embree, AccelKind::Bvh, AccelKind::BruteForce,
                                           AccelKind::Grid),
                         [](const auto& p) { return std::string(accelName(p.param)); });

}  // namespace
}  // namespace glint
