// Embree against the brute-force oracle on random rays through a scene with every shape kind.
#include <gtest/gtest.h>

#include "accel/accelerator.h"
#include "core/hash.h"
#include "test_util.h"

namespace glint {
namespace {

TEST(BackendAgreement, EmbreeMatchesBruteForceOnRandomRays) {
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}},
    "groups": {"g": [{"type": "box", "min": [-0.5,-0.5,-0.5], "max": [0.5,0.5,0.5], "material": "m"},
                     {"type": "sphere", "center": [0,1,0], "radius": 0.4, "material": "m"}]},
    "objects": [
      {"type": "plane", "point": [0,-3,0], "normal": [0,1,0], "material": "m"},
      {"type": "sphere", "center": [1,0,0], "radius": 0.7, "material": "m"},
      {"type": "quad", "corner": [-2,-2,-1], "edge1": [1,0,0], "edge2": [0,1,0.5], "material": "m"},
      {"type": "mesh", "file": "meshes/wuson.obj", "material": "m", "transform": {"scale": [2,2,2]}},
      {"type": "instance", "group": "g", "transform": {"translate": [-1.5,1,0], "rotate": [1,1,0,30]}},
      {"type": "instance", "group": "g", "transform": {"matrix": [1,0.3,0,1.5, 0,1,0,-1.5, 0,0,2,0, 0,0,0,1]}}
    ]})");
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  constexpr int kRays = 4000;
  int hits = 0, disagreements = 0;
  for (int i = 0; i < kRays; ++i) {
    // Origins uniform in [−3, 3]³, directions towards a point in [−1.5, 1.5]³: most rays hit.
    auto u = [&](int k) { return toUnitFloat(hashKey(42, i, k)); };
    Ray r;
    r.o = {6 * u(0) - 3, 6 * u(1) - 3, 6 * u(2) - 3};
    r.d = Vec3f{3 * u(3) - 1.5f, 3 * u(4) - 1.5f, 3 * u(5) - 1.5f} - r.o;
    const Hit a = embree->intersect(r), b = brute->intersect(r);
    hits += bool(a);
    const bool agree =
        bool(a) == bool(b) && (!a || (a.geomId == b.geomId && a.instId == b.instId &&
                                      std::fabs(a.t - b.t) <= 1e-4f * std::max(1.0f, a.t)));
    // Two triangles sharing an edge may both claim a ray through it: accept equal t.
    const bool tie = bool(a) && bool(b) && std::fabs(a.t - b.t) <= 1e-4f * std::max(1.0f, a.t);
    if (!agree && !tie) ++disagreements;
    EXPECT_EQ(embree->occluded(r), bool(b)) << "ray " << i;
  }
  EXPECT_GT(hits, kRays / 2);  // the test must exercise hits, not only misses
  EXPECT_EQ(disagreements, 0);
}

}  // namespace
}  // namespace glint
