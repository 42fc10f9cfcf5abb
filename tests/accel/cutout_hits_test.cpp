// Opacity cut-outs in every backend (accel/cutout_hits.h, Embree's filter functions): rays pass
// through the holes of quads, spheres, triangle meshes and instanced geometry alike, for closest
// hits and for occlusion.
#include "accel/cutout_hits.h"

#include <gtest/gtest.h>

#include <cmath>

#include "accel/accelerator.h"
#include "core/hash.h"
#include "test_util.h"

namespace glint {
namespace {

// Everything in front of a wall at z = −3, cut by test::writeHalfMatte (holes where u < 0.5):
// a unit quad at the origin (u = x, v = y), a sphere at x = 5 (u = φ/2π with φ = atan2(z, x):
// its z > 0 half is the hole, its z < 0 half solid), a unit square mesh at x = −5 with its own
// uvs, and the quad again through an instance moved 5 down.
Scene cutScene() {
  // The eye at the origin: render space is world space (io/placement.h).
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"},
                  "cut": {"type": "phong", "opacity": {"image": ")" +
                             test::writeHalfMatte() + R"("}}},
    "groups": {"g": [{"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0],
                      "material": "cut"}]},
    "objects": [
      {"type": "quad", "corner": [-10,-10,-3], "edge1": [20,0,0], "edge2": [0,20,0], "material": "m"},
      {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0], "material": "cut"},
      {"type": "sphere", "center": [5,0,0], "radius": 1, "material": "cut"},
      {"type": "mesh", "positions": [[-5,0,0],[-4,0,0],[-4,1,0],[-5,1,0]],
       "indices": [[0,1,2],[0,2,3]], "uvs": [[0,0],[1,0],[1,1],[0,1]], "material": "cut"},
      {"type": "instance", "group": "g", "transform": {"translate": [0,-5,0]}}
    ]})");
}

Ray downZ(float x, float y) {
  Ray r;
  r.o = {x, y, 5};
  r.d = {0, 0, -1};
  return r;
}

TEST(CutoutHits, EveryBackendPassesThroughHolesAndStopsOnSolidParts) {
  const Scene s = cutScene();
  ASSERT_TRUE(s.features.cutouts);
  struct Case {
    const char* what;
    float x, y;
    float t;  // expected distance from z = 5
  };
  // The wall is 8 away; a kept surface at z = 0 is 5 away.
  const float sphereFar = 5 + std::sqrt(1 - 0.3f * 0.3f);  // z = −√(1 − y²): its solid half
  const Case cases[] = {{"quad hole", 0.25f, 0.5f, 8},
                        {"quad solid", 0.75f, 0.5f, 5},
                        {"sphere: through the near hole to the far side", 5, 0.3f, sphereFar},
                        {"mesh hole", -4.75f, 0.5f, 8},
                        {"mesh solid", -4.25f, 0.5f, 5},
                        {"instance hole", 0.25f, -4.5f, 8},
                        {"instance solid", 0.75f, -4.5f, 5}};
  for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh, AccelKind::BruteForce}) {
    const auto accel = makeAccelerator(kind, s);
    for (const Case& c : cases) {
      const Ray r = downZ(c.x, c.y);
      const Hit hit = accel->intersect(r);
      ASSERT_TRUE(bool(hit)) << accel->name() << ": " << c.what;
      EXPECT_NEAR(hit.t, c.t, 1e-5f * c.t) << accel->name() << ": " << c.what;
      // A shadow ray that ends just before the expected surface is not blocked; one that
      // reaches past it is.
      Ray shortOf = r;
      shortOf.tMax = c.t - 0.01f;
      EXPECT_FALSE(accel->occluded(shortOf)) << accel->name() << ": " << c.what;
      Ray past = r;
      past.tMax = c.t + 0.01f;
      EXPECT_TRUE(accel->occluded(past)) << accel->name() << ": " << c.what;
    }
    // The packet paths: a bundle of the same rays, closest hits and occlusion.
    std::vector<Ray> rays;
    for (const Case& c : cases) rays.push_back(downZ(c.x, c.y));
    std::vector<Hit> hits(rays.size());
    accel->intersectCoherent(rays.data(), hits.data(), rays.size());
    std::unique_ptr<bool[]> blocked(new bool[rays.size()]);
    for (Ray& r : rays) r.tMax = 6;  // past z = 0, short of the wall
    accel->occludedCoherent(rays.data(), blocked.get(), rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      EXPECT_NEAR(hits[i].t, cases[i].t, 1e-5f * cases[i].t)
          << accel->name() << " coherent: " << cases[i].what;
      EXPECT_EQ(blocked[i], cases[i].t < 6) << accel->name() << " coherent: " << cases[i].what;
    }
  }
}

TEST(CutoutHits, BackendsAgreeOnRandomRays) {
  const Scene s = cutScene();
  Scene solid = cutScene();
  solid.features.cutouts = false;  // the same geometry with its holes filled
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  const auto bvh = makeAccelerator(AccelKind::Bvh, s);
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  const auto filled = makeAccelerator(AccelKind::BruteForce, solid);
  constexpr int kRays = 20000;
  int throughHoles = 0, disagreements = 0;
  for (int i = 0; i < kRays; ++i) {
    // From around z = 5 towards the shapes' region, from all sides of it.
    auto u = [&](int k) { return toUnitFloat(hashKey(7, i, k)); };
    Ray r;
    r.o = {14 * u(0) - 7, 8 * u(1) - 6, 4 + 2 * u(2)};
    r.d = Vec3f{12 * u(3) - 6, 7 * u(4) - 6, 2 * u(5) - 1.5f} - r.o;
    const Hit reference = brute->intersect(r);
    throughHoles += filled->intersect(r).t < reference.t;
    for (const Accelerator* a : {embree.get(), bvh.get()}) {
      const Hit h = a->intersect(r);
      // Equal ids and t within the backends' rounding (their triangle tests differ).
      const bool same = bool(h) == bool(reference) &&
                        (!h || (h.geomId == reference.geomId && h.instId == reference.instId &&
                                std::fabs(h.t - reference.t) <= 1e-4f * std::max(1.0f, h.t)));
      disagreements += !same;
      disagreements += a->occluded(r) != bool(reference);
    }
  }
  // Rays must pass through holes to something behind them, or the test shows nothing: the
  // shapes cover a small part of where the rays go (906 of these 20000 rays, 4.5 %, pass a hole).
  EXPECT_GT(throughHoles, kRays / 50);
  // Hole edges are where a hit's (u, v) is compared with 0.5 after filtering: rays within an
  // ulp of one may go either way between backends; none of 20000 random rays came that close.
  EXPECT_EQ(disagreements, 0);
}

}  // namespace
}  // namespace glint
