// Embree against the brute-force oracle on random rays through a scene with every shape kind,
// and Embree's coherent streams against its own single-ray queries.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "accel/accelerator.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/sphere_hierarchy.h"
#include "accel/uniform_grid.h"
#include "core/hash.h"
#include "test_util.h"

namespace glint {
namespace {

// Every shape kind Embree holds for Glint: a plane (outside Embree), user spheres and quads,
// a triangle mesh, CSG solids (in the world and in instances), and instances of a group.
Scene everyShapeKind() {
  return test::sceneFromText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}},
    "groups": {"g": [{"type": "box", "min": [-0.5,-0.5,-0.5], "max": [0.5,0.5,0.5], "material": "m"},
                     {"type": "sphere", "center": [0,1,0], "radius": 0.4, "material": "m"},
                     {"type": "csg", "op": "difference", "material": "m", "operands": [
                       {"type": "box", "min": [-0.4,-1.4,-0.4], "max": [0.4,-0.6,0.4]},
                       {"type": "sphere", "center": [0,-1,0.4], "radius": 0.3}]}]},
    "objects": [
      {"type": "plane", "point": [0,-3,0], "normal": [0,1,0], "material": "m"},
      {"type": "sphere", "center": [1,0,0], "radius": 0.7, "material": "m"},
      {"type": "csg", "op": "intersection", "material": "m", "operands": [
        {"type": "sphere", "center": [-0.5,-1.5,0], "radius": 1}, {"type": "sphere", "center": [0.5,-1.5,0], "radius": 1}]},
      {"type": "quad", "corner": [-2,-2,-1], "edge1": [1,0,0], "edge2": [0,1,0.5], "material": "m"},
      {"type": "mesh", "file": "meshes/wuson.obj", "material": "m", "transform": {"scale": [2,2,2]}},
      {"type": "instance", "group": "g", "transform": {"translate": [-1.5,1,0], "rotate": [1,1,0,30]}},
      {"type": "instance", "group": "g", "transform": {"matrix": [1,0.3,0,1.5, 0,1,0,-1.5, 0,0,2,0, 0,0,0,1]}}
    ]})");
}

// `fast` against the brute-force oracle on 4000 random rays through everyShapeKind().
void expectAgreesWithBruteForce(const Scene& s, const Accelerator& fast) {
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  constexpr int kRays = 4000;
  int hits = 0, disagreements = 0;
  for (int i = 0; i < kRays; ++i) {
    // Origins uniform in [−3, 3]³, directions towards a point in [−1.5, 1.5]³: most rays hit.
    auto u = [&](int k) { return toUnitFloat(hashKey(42, i, k)); };
    Ray r;
    r.o = {6 * u(0) - 3, 6 * u(1) - 3, 6 * u(2) - 3};
    r.d = Vec3f{3 * u(3) - 1.5f, 3 * u(4) - 1.5f, 3 * u(5) - 1.5f} - r.o;
    const Hit a = fast.intersect(r), b = brute->intersect(r);
    hits += bool(a);
    const bool agree =
        bool(a) == bool(b) && (!a || (a.geomId == b.geomId && a.instId == b.instId &&
                                      std::fabs(a.t - b.t) <= 1e-4f * std::max(1.0f, a.t)));
    // Two triangles sharing an edge may both claim a ray through it: accept equal t.
    const bool tie = bool(a) && bool(b) && std::fabs(a.t - b.t) <= 1e-4f * std::max(1.0f, a.t);
    if (!agree && !tie) ++disagreements;
    EXPECT_EQ(fast.occluded(r), bool(b)) << fast.name() << " ray " << i;
  }
  EXPECT_GT(hits, kRays / 2);  // the test must exercise hits, not only misses
  EXPECT_EQ(disagreements, 0) << fast.name();
}

TEST(BackendAgreement, EmbreeMatchesBruteForceOnRandomRays) {
  const Scene s = everyShapeKind();
  expectAgreesWithBruteForce(s, *makeAccelerator(AccelKind::Embree, s));
}

// The grid at its default resolution (⌈∛n⌉: 16 cells per axis for the world's 3 700 triangles),
// at one cell (a plain loop), and at resolutions that put many cells across every primitive:
// the 3D-DDA must visit every cell a ray crosses, and mailboxing must skip only repeats.
TEST(BackendAgreement, UniformGridMatchesBruteForceAtEveryResolution) {
  const Scene s = everyShapeKind();
  for (int resolution : {0, 1, 2, 7, 64}) {
    SCOPED_TRACE(resolution);
    expectAgreesWithBruteForce(s, UniformGrid(s, resolution));
  }
}

// The octree at its default depth (⌈log₂(n)/3⌉ = 4 levels here), at none (one leaf), and one
// and seven levels deep, by both walks; the k-d tree as built by its SAH.
TEST(BackendAgreement, OctreeAndKdTreeMatchBruteForce) {
  const Scene s = everyShapeKind();
  for (int levels : {0, 1, 7}) {
    SCOPED_TRACE(levels);
    expectAgreesWithBruteForce(s, Octree(s, levels));
    expectAgreesWithBruteForce(s, Octree(s, levels, Octree::Walk::GenerateAndTest));
  }
  expectAgreesWithBruteForce(s, KdTree(s));
  expectAgreesWithBruteForce(s, RayClassification(s));
}

// Ray coherence at its default resolution and at 1 and 32 classes per face edge: random rays
// carry no origin (the fallback); rays tagged with an origin are in tests/accel/ray_coherence_test.
TEST(BackendAgreement, RayCoherenceMatchesBruteForce) {
  const Scene s = everyShapeKind();
  for (int resolution : {0, 1, 32}) {
    SCOPED_TRACE(resolution);
    expectAgreesWithBruteForce(s, RayCoherence(s, resolution));
  }
}

// The sphere hierarchy: every shape kind behind its own bounding sphere, instances included.
TEST(BackendAgreement, SphereHierarchyMatchesBruteForce) {
  const Scene s = everyShapeKind();
  expectAgreesWithBruteForce(s, SphereHierarchy(s));
}

// The renderer traces camera rays and shadow rays as coherent streams (packets inside Embree):
// every ray must get the answer rtcIntersect1 / rtcOccluded1 gives it. Bundles of 16 rays leave
// from close together towards one point, as a chunk's shadow rays towards a light do; some
// are segments ending short of the point (shadow rays), some unbounded. All 4000 go in one call,
// so the backend's own chunking is crossed too.
TEST(BackendAgreement, EmbreeStreamsAnswerAsOneRayAtATime) {
  const Scene s = everyShapeKind();
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  constexpr int kBundles = 250, kPerBundle = 16;
  std::vector<Ray> rays;
  for (int b = 0; b < kBundles; ++b) {
    auto u = [&](int i, int k) { return toUnitFloat(hashKey(7, b * kPerBundle + i, k)); };
    const Vec3f base{6 * u(0, 0) - 3, 6 * u(0, 1) - 3, 6 * u(0, 2) - 3};
    const Vec3f target{6 * u(0, 3) - 3, 6 * u(0, 4) - 3, 6 * u(0, 5) - 3};
    for (int i = 0; i < kPerBundle; ++i) {
      Ray r;
      r.o = base + 0.1f * Vec3f{u(i, 6) - 0.5f, u(i, 7) - 0.5f, u(i, 8) - 0.5f};
      r.d = target - r.o;
      r.tMax = b % 2 ? 0.999f : kInfinity;
      rays.push_back(r);
    }
  }
  std::vector<Hit> hits(rays.size());
  std::unique_ptr<bool[]> blocked(new bool[rays.size()]);
  embree->intersectCoherent(rays.data(), hits.data(), rays.size());
  embree->occludedCoherent(rays.data(), blocked.get(), rays.size());
  int hitCount = 0, blockedCount = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit one = embree->intersect(rays[i]);
    hitCount += bool(one);
    blockedCount += blocked[i];
    ASSERT_EQ(bool(hits[i]), bool(one)) << "ray " << i;
    if (one) {
      EXPECT_EQ(hits[i].geomId, one.geomId) << "ray " << i;
      EXPECT_EQ(hits[i].instId, one.instId) << "ray " << i;
      // Embree's packet kernels may round t differently from its single-ray kernel.
      EXPECT_NEAR(hits[i].t, one.t, 1e-5f * std::max(1.0f, one.t)) << "ray " << i;
    }
    EXPECT_EQ(blocked[i], embree->occluded(rays[i])) << "ray " << i;
  }
  // Both answers must be exercised: hits and misses, blocked and clear segments.
  EXPECT_GT(hitCount, 400);
  EXPECT_LT(hitCount, 3600);
  EXPECT_GT(blockedCount, 400);
  EXPECT_LT(blockedCount, 3600);
}

}  // namespace
}  // namespace glint
