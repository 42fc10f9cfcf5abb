// The octree's subdivision rule (seed 002 §9.2.2) and its bound on references, on scenes built
// for them.
#include "accel/octree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "accel/cross_check.h"

#include "accel/triangle_scenes.h"
#include "core/hash.h"

namespace glint {
namespace {

using test::triangles;
using Walk = Octree::Walk;

constexpr Walk kWalks[] = {Walk::GenerateAndTest, Walk::MidPlane};

// `octree` against brute force on `ray`: the same closest hit (two surfaces at the same t may
// both claim it) and the same occlusion answer. Counts brute force's hits in `hits`.
void expectAgreesWithBruteForce(const Accelerator& octree, const Accelerator& brute, const Ray& ray,
                                int& hits) {
  const Hit a = octree.intersect(ray), b = brute.intersect(ray);
  hits += bool(b);
  ASSERT_EQ(bool(a), bool(b)) << octree.name() << " ray " << formatRay(ray);
  if (a && a.geomId == b.geomId) {
    EXPECT_EQ(a.t, b.t) << octree.name();
  } else if (a) {
    EXPECT_NEAR(a.t, b.t, 1e-5f * std::max(1.0f, b.t)) << octree.name();
  }
  EXPECT_EQ(octree.occluded(ray), brute.occluded(ray)) << octree.name();
}

TEST(Octree, CutsPartialCellsDownToTheSeedsDepth) {
  // 1000 triangles 1/100 of the cube wide: K = ⌈log₂(1000)/3⌉ = 4 levels (16 cells per axis at
  // the finest, the grid's ⌈∛n⌉ = 10 rounded up to a power of two). At level 3 (512 cells) the
  // average cell holds about 2 triangles, so some hold more and are cut to level 4.
  const Scene s = triangles(1000, false);
  const Octree octree(s);
  EXPECT_EQ(octree.stats().maxDepth, 4u);
  EXPECT_EQ(octree.stats().primitives, 1000u);
  // Only partial cells are cut, so far fewer than the 16³ cells of a full level 4.
  EXPECT_LT(octree.stats().leaves, 4096u);
  // Triangles straddle a mid-plane at the finest level with probability about 3·(1/100)/(1/16):
  // most are listed once.
  EXPECT_LT(octree.stats().references, 2000u);
  // Told to stop at one level, it makes the root and its eight octants.
  const Octree shallow(s, 1);
  EXPECT_EQ(shallow.stats().nodes, 9u);
}

TEST(Octree, DoesNotCutWhatItCannotSeparate) {
  // 50 concentric spheres of radius 0.3 to 0.5 about the root cube's centre: every octant of
  // the root (a cube of side 0.5 with a corner at the centre, its far corner 0.5·√3 = 0.87 away)
  // holds a part of every surface, so cutting would list each in every cell and separate
  // nothing: the root stays one leaf.
  std::string objects;
  for (int i = 0; i < 50; ++i)
    objects += std::string(i ? "," : "") +
               R"({"type": "sphere", "center": [0,0,0], "material": "m", "radius": )" +
               std::to_string(0.3 + 0.004 * i) + "}";
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}}, "objects": [)" +
                                      objects + "]}");
  const Octree octree(s);
  EXPECT_EQ(octree.stats().nodes, 1u);
  EXPECT_EQ(octree.stats().references, 50u);
}

TEST(Octree, ReferencesStayBoundedWhenEveryPrimitiveSpansTheScene) {
  // 20 000 triangles fanned across the cube (each box spans it in x and y): cut down to the
  // seed's ⌈log₂(20 000)/3⌉ = 5 levels they would be listed in most cells of every level. The
  // octree stops cutting at the budget of 64 per primitive plus 2²⁰, and still finds the
  // closest hit.
  const Scene s = triangles(20000, true);
  const Octree octree(s);
  EXPECT_LE(double(octree.stats().references), 64.0 * 20000 + (1 << 20));
  test::expectFindsTheFansClosestHit(s, octree);
}

// Three concentric spheres (radii 1, 1.01, 1.02) and a small one at (1.5, 1.5, 1.5) that puts
// the root cube's centre off theirs: the cube [−1.02, 1.6]³ (centre 0.29) is cut, and its octant
// [−1.02, 0.29]³ again, into cells of side 0.655; the one holding the centre,
// [−0.365, 0.29]³, has its farthest corner 0.63 from the centre, inside all three spheres.
Scene nestedSpheres() {
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"},
                {"type": "sphere", "center": [0,0,0], "radius": 1.01, "material": "m"},
                {"type": "sphere", "center": [0,0,0], "radius": 1.02, "material": "m"},
                {"type": "sphere", "center": [1.5,1.5,1.5], "radius": 0.1, "material": "m"}]})");
}

TEST(Octree, FullCellsAreLeavesWithNothingInThem) {
  // Seed 002 §9.2.2: a cell inside a solid is not cut and lists nothing, like an empty one.
  // Four levels deep, the cells around the centre are full and those in the cube's corners
  // beyond all four spheres empty.
  const Octree octree(nestedSpheres(), 4);
  EXPECT_GE(octree.stats().fullLeaves, 1u);
  EXPECT_GE(octree.stats().emptyLeaves, 1u);
  EXPECT_LE(octree.stats().fullLeaves + octree.stats().emptyLeaves, octree.stats().leaves);
}

TEST(Octree, RayFromInsideAFullCellFindsTheSurface) {
  // From the centre, in the full cell [−0.365, 0.29]³: the nearest surface is the unit
  // sphere's, at t = 1 along any unit direction; nothing is in the way out of the cube either.
  const Scene s = nestedSpheres();
  for (Walk walk : kWalks) {
    const Octree octree(s, 4, walk);
    SCOPED_TRACE(octree.name());
    for (const Vec3f d : {Vec3f{0.3f, 0.5f, 0.8f}, Vec3f{-1, 0, 0}, Vec3f{-1, -1, -1}}) {
      const Hit h = octree.intersect(Ray{{0, 0, 0}, normalize(d)});
      ASSERT_TRUE(h);
      EXPECT_EQ(h.geomId, 0u);
      EXPECT_NEAR(h.t, 1, 1e-6);
      // A segment ending short of it is clear.
      Ray shortRay{{0, 0, 0}, normalize(d)};
      shortRay.tMax = 0.99f;
      EXPECT_FALSE(octree.occluded(shortRay));
    }
  }
}

// Surfaces on the cells' faces, edges and corners: eight spheres of radius 0.5 centred at
// (±0.5, ±0.5, ±0.5), each touching the three mid-planes of the root cube and its neighbours; a
// square in the mid-plane x = 0 and a triangle in y = 0. Symmetric about the origin, so the root
// cube is centred there exactly.
Scene surfacesOnTheMidPlanes() {
  std::string objects;
  for (int k = 0; k < 8; ++k)
    objects += R"({"type": "sphere", "material": "m", "radius": 0.5, "center": )" +
               test::vec((k & 1) ? 0.5f : -0.5f, (k & 2) ? 0.5f : -0.5f, (k & 4) ? 0.5f : -0.5f) +
               "},";
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}}, "objects": [)" +
                             objects + R"(
      {"type": "quad", "corner": [0,-0.25,-0.25], "edge1": [0,0.5,0], "edge2": [0,0,0.5], "material": "m"},
      {"type": "mesh", "material": "m", "positions": [[-1,0,-1],[1,0,-1],[-1,0,1]], "indices": [[0,1,2]]}]})");
}

TEST(Octree, RaysGrazingFacesEdgesAndCornersAgreeWithBruteForce) {
  const Scene s = surfacesOnTheMidPlanes();
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  // The cells' faces as the octree computes them: the root's mid-planes at 0 and the next
  // level's at ±half/2 (the root cube's half side, as the build takes it).
  Bounds3f box;
  for (const PrimitiveBox& p : groupPrimitives(s, 0, [](uint32_t) { return Bounds3f{}; }))
    box.extend(p.box);
  const float half = 0.5f * maxComponent(box.hi - box.lo) * (1 + 1e-5f);
  const float planes[] = {0, half / 2, -half / 2};
  for (int levels : {0, 3, 5})
    for (Walk walk : kWalks) {
      const Octree octree(s, levels, walk);
      SCOPED_TRACE(std::string(octree.name()) + " levels " + std::to_string(levels));
      int hits = 0;
      for (uint32_t i = 0; i < 1500; ++i) {
        const auto u = [&](int k) { return toUnitFloat(hashKey(17, i, k)); };
        const float p = planes[i % 3], q = planes[(i / 3) % 3], r = planes[(i / 9) % 3];
        const int a = int(i / 27) % 3, b = (a + 1) % 3;
        // Origins in [−3, 3]³, most outside the root cube.
        Vec3f o{6 * u(0) - 3, 6 * u(1) - 3, 6 * u(2) - 3};
        Vec3f d{u(3) - 0.5f, u(4) - 0.5f, u(5) - 0.5f};
        // Along a face: in the plane of axis a, the direction's a-component zero.
        Ray face{o, d};
        face.o[a] = p;
        face.d[a] = 0;
        expectAgreesWithBruteForce(octree, *brute, face, hits);
        // Along an edge: on the line where the planes of axes a and b meet.
        Ray edge{o, {0, 0, 0}};
        edge.o[a] = p;
        edge.o[b] = q;
        edge.d[3 - a - b] = u(6) < 0.5f ? 1.0f : -1.0f;
        expectAgreesWithBruteForce(octree, *brute, edge, hits);
        // Through a corner where three planes meet: o + 2·d is the corner up to rounding.
        const Vec3f corner{p, q, r};
        expectAgreesWithBruteForce(octree, *brute, Ray{corner - 2.0f * d, d}, hits);
        // From a corner, and from a point on a face, out in every direction.
        expectAgreesWithBruteForce(octree, *brute, Ray{corner, d}, hits);
        expectAgreesWithBruteForce(octree, *brute, Ray{face.o, d}, hits);
      }
      // Most of the 7 500 rays meet a surface: the agreement is about hits, not misses.
      EXPECT_GT(hits, 3750);
    }
}

}  // namespace
}  // namespace glint
