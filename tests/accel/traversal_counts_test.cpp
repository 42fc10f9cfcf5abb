// What Glint's own structures count of a traversal (accel/two_level.h), on scenes small enough
// to count by hand, and seed 002 §9.2.1's bound on the cells a grid ray visits.
#include "accel/two_level.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "accel/triangle_scenes.h"
#include "core/hash.h"

namespace glint {
namespace {

constexpr AccelKind kCounted[] = {AccelKind::Bvh,
                                  AccelKind::Grid,
                                  AccelKind::Octree,
                                  AccelKind::KdTree,
                                  AccelKind::OctreeGenerateAndTest,
                                  AccelKind::RayClass,
                                  AccelKind::Coherence,
                                  AccelKind::Spheres};

const CountingTraversal& counting(const Accelerator& accel) {
  return dynamic_cast<const CountingTraversal&>(accel);
}

// A lattice of 3 x 3 x 3 spheres of radius 0.2, one unit apart, centred at (0, 0, -10); the eye
// at the origin, so render space is world space.
Scene lattice() {
  std::string objects;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        objects += std::string(objects.empty() ? "" : ",") +
                   R"({"type": "sphere", "radius": 0.2, "material": "m", "center": )" +
                   test::vec(float(i), float(j), float(k - 10)) + "}";
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}}, "objects": [)" +
                             objects + "]}");
}

TEST(TraversalCounts, OneSphereIsOneNodeAndOneTestInEveryStructure) {
  // One primitive: the BVH's root is a leaf, the grid has ⌈∛1⌉ = 1 cell, the octree's depth is
  // ⌈log₂(1)/3⌉ = 0 and the k-d tree makes no split. A ray through the sphere visits that one
  // node and tests the sphere once; a ray past its box tests nothing.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}]})");
  for (AccelKind kind : kCounted) {
    SCOPED_TRACE(accelName(kind));
    const auto accel = makeAccelerator(kind, s);
    TraversalCounts through, past;
    const Hit hit = counting(*accel).intersectCounting(Ray{{0, 0, 0}, {0, 0, -1}}, through);
    EXPECT_NEAR(hit.t, 4, 1e-5);  // the sphere's near side, 5 - 1 away
    EXPECT_EQ(through.steps, 1u);
    EXPECT_EQ(through.tests, 1u);
    EXPECT_FALSE(counting(*accel).intersectCounting(Ray{{0, 0, 0}, {0, 1, 0}}, past));
    EXPECT_EQ(past.tests, 0u);
    EXPECT_LE(past.steps, 1u);  // the BVH tests its root's box; the others stop before it
  }
}

TEST(TraversalCounts, AGridRayAlongARowVisitsItsThreeCellsAndTestsEachSphereOnce) {
  // 27 spheres: R = ⌈∛27⌉ = 3 cells per axis over the box [-1.2, 1.2]² × [-11.2, -8.8], each
  // cell 0.8 wide holding one sphere. A ray along x at y = 0.3 (inside the middle row of cells,
  // past the spheres of radius 0.2 at y = 0) crosses the row's 3 cells and misses all 3 spheres.
  const Scene s = lattice();
  const auto grid = makeAccelerator(AccelKind::Grid, s);
  TraversalCounts counts;
  EXPECT_FALSE(counting(*grid).intersectCounting(Ray{{-5, 0.3f, -10}, {1, 0, 0}}, counts));
  EXPECT_EQ(counts.steps, 3u);
  EXPECT_EQ(counts.tests, 3u);
}

TEST(TraversalCounts, NoGridRayVisitsMoreThanGlintsBoundOfCells) {
  // Glint's bound: a 3D-DDA enters at most 3R − 2 cells of an R × R × R grid, 7 for R = 3 (each
  // step crosses one plane; a ray crosses at most R − 1 planes per axis), which a DDA that
  // revisited or skipped back a cell would exceed: 10⁴ rays from around the lattice in every
  // direction. Seed 002 §9.2.1 writes the bound as k ≤ 1 + 7(R − 1) (eq. 9.1, 15 for R = 3),
  // O(R) either way.
  const Scene s = lattice();
  const auto grid = makeAccelerator(AccelKind::Grid, s);
  uint64_t most = 0;
  for (uint32_t i = 0; i < 10000; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(11, i, k)); };
    const Vec3f o{6 * u(0) - 3, 6 * u(1) - 3, 6 * u(2) - 13};
    const Vec3f target{2.4f * u(3) - 1.2f, 2.4f * u(4) - 1.2f, 2.4f * u(5) - 11.2f};
    TraversalCounts counts;
    counting(*grid).intersectCounting(Ray{o, normalize(target - o)}, counts);
    most = std::max(most, counts.steps);
  }
  EXPECT_LE(most, 7u);
  EXPECT_GE(most, 5u);  // some ray does cross the grid obliquely (the bound is not vacuous)
}

TEST(TraversalCounts, CountingChangesNoHit) {
  // The counting traversal is the render's with counters: the same hit on every ray.
  const Scene s = test::triangles(1000, false);
  for (AccelKind kind : kCounted) {
    SCOPED_TRACE(accelName(kind));
    const auto accel = makeAccelerator(kind, s);
    TraversalCounts counts;
    int hits = 0;
    for (uint32_t i = 0; i < 2000; ++i) {
      const auto u = [&](int k) { return toUnitFloat(hashKey(12, i, k)); };
      const Vec3f o{3 * u(0) - 1, 3 * u(1) - 1, 3 * u(2) - 1};
      const Vec3f target{u(3), u(4), u(5)};
      const Ray r{o, normalize(target - o)};
      const Hit a = accel->intersect(r), b = counting(*accel).intersectCounting(r, counts);
      ASSERT_EQ(a.t, b.t);
      ASSERT_EQ(a.primId, b.primId);
      hits += bool(a);
    }
    // Every ray aims into the triangles' cube, so each visits a node or cell; some hit.
    EXPECT_GE(counts.steps, 2000u);
    EXPECT_GT(hits, 20);
  }
}

}  // namespace
}  // namespace glint
