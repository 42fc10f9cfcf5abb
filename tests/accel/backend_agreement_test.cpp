// Embree against the brute-force oracle on random rays through a scene with every shape kind,
// and Embree's coherent streams against its own single-ray queries.
#include <gtest/gtest.h>

#include <bit>
#include <memory>
#include <string>
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

// `fast` against the brute-force oracle on 4000 random rays through everyShapeKind() (a
// twentieth under AddressSanitizer).
void expectAgreesWithBruteForce(const Scene& s, const Accelerator& fast) {
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  constexpr int kRays = test::agreementRays(4000);
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

// Two crossing planes (the second cut by test::writeHalfMatte when `cut`), for the plane loops.
// The eye at the origin: render space is world space (io/placement.h).
Scene crossingPlanes(bool cut) {
  // A scene turns its cut-out path on when any material has an opacity map, used or not.
  const std::string cutMaterial = cut ? R"(, "cut": {"type": "phong", "opacity": {"image": ")" +
                                            test::writeHalfMatte() + R"("}})"
                                      : "";
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"})" +
                             cutMaterial + R"(},
    "objects": [
      {"type": "plane", "point": [0,-1,0], "normal": [0,1,0], "material": "m"},
      {"type": "plane", "point": [0,0,-2], "normal": [0,0.6,0.8], "material": ")" +
                             (cut ? "cut" : "m") + R"("}
    ]})");
}

// The plane loops over a stream answer ray by ray as the one-ray loops do, to the bit: the same
// t, the same plane where both are met, a closer hit already found kept.
TEST(BackendAgreement, PlaneStreamsAnswerAsOneRayAtATime) {
  for (const bool cut : {false, true}) {
    const Scene s = crossingPlanes(cut);
    ASSERT_EQ(s.features.cutouts, cut);
    constexpr int kRays = 3000;
    std::vector<Ray> rays(kRays);
    std::vector<Hit> hits(kRays), one(kRays);
    for (int i = 0; i < kRays; ++i) {
      auto u = [&](int k) { return toUnitFloat(hashKey(11, i, k)); };
      rays[i].o = {8 * u(0) - 4, 4 * u(1) - 1, 8 * u(2) - 4};
      rays[i].d = {2 * u(3) - 1, 2 * u(4) - 1, 2 * u(5) - 1};
      rays[i].tMax = i % 3 ? kInfinity : 4 * u(6);
      // A third of the rays arrive with a closer hit of something else, which a plane must not
      // replace unless it is closer still.
      if (i % 3 == 1) hits[i] = Hit{3 * u(7), 0.25f, 0.5f, 7, 3, kInvalidId};
      one[i] = hits[i];
      intersectPlanes(s, rays[i], one[i]);
    }
    intersectPlanes(s, rays.data(), hits.data(), rays.size());
    std::unique_ptr<bool[]> blocked(new bool[kRays]);
    occludedByPlanes(s, rays.data(), blocked.get(), rays.size());
    int onFirst = 0, onSecond = 0, kept = 0, blockedCount = 0;
    for (int i = 0; i < kRays; ++i) {
      ASSERT_EQ(std::bit_cast<uint32_t>(hits[i].t), std::bit_cast<uint32_t>(one[i].t)) << i;
      ASSERT_EQ(hits[i].geomId, one[i].geomId) << i;
      ASSERT_EQ(hits[i].primId, one[i].primId) << i;
      ASSERT_EQ(hits[i].u, one[i].u) << i;
      ASSERT_EQ(blocked[i], occludedByPlanes(s, rays[i])) << i;
      onFirst += hits[i].geomId == s.planeGeometries[0];
      onSecond += hits[i].geomId == s.planeGeometries[1];
      kept += hits[i].geomId == 7;
      blockedCount += blocked[i];
    }
    // Every branch is taken: either plane nearest, the earlier hit kept, rays blocked and clear.
    EXPECT_GT(onFirst, kRays / 10) << cut;
    EXPECT_GT(onSecond, kRays / 20) << cut;  // the matte's holes let about half through
    EXPECT_GT(kept, kRays / 20) << cut;
    EXPECT_GT(blockedCount, kRays / 10) << cut;
    EXPECT_LT(blockedCount, kRays - kRays / 10) << cut;
  }
  // Straight down from y = 3 at z = 5: the floor y = −1 is 4 away, nearer than the tilted plane
  // (0.6·y + 0.8·(z + 2) = 0 at y = −28/3).
  const Scene s = crossingPlanes(false);
  Ray down;
  down.o = {0, 3, 5};
  down.d = {0, -1, 0};
  Hit h;
  intersectPlanes(s, &down, &h, 1);
  EXPECT_EQ(h.t, 4.0f);  // exact: (−1 − 3)·1 / −1
  EXPECT_EQ(h.geomId, s.planeGeometries[0]);
}

}  // namespace
}  // namespace glint
