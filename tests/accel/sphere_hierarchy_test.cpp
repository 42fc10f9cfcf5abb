// The bounding-sphere hierarchy (`--accel spheres`) against Embree and the brute-force oracle on
// generated scenes, its tree's enclosure invariants, and rays grazing its spheres.
#include "accel/sphere_hierarchy.h"

#include <gtest/gtest.h>

#include <sstream>

#include "accel/brute_force.h"
#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/soup_scenes.h"
#include "core/hash.h"
#include "test_util.h"

namespace glint {
namespace {

using test::preciseVec;
using test::rnd;
using test::sceneWith;
using test::soup;

std::string spheres(uint64_t key, int count) {
  std::string objects;
  for (int i = 0; i < count; ++i)
    objects += (i ? "," : "") + std::string(R"({"type": "sphere", "material": "m", "center": )") +
               preciseVec(2 * rnd(key, i, 0) - 1, 2 * rnd(key, i, 1) - 1, 2 * rnd(key, i, 2) - 1) +
               ", \"radius\": " + std::to_string(0.01 + 0.1 * rnd(key, i, 3)) + "}";
  return objects;
}

// Soup, spheres, instances of a group (one rotating over the shutter), a moving sphere and a
// deforming triangle: every path into the tree (exact spheres, triangle spheres, box spheres of
// moving things and instances).
std::string mixedScene() {
  std::string objects = soup(3, 300, 0.3f) + "," + spheres(2, 100);
  for (int i = 0; i < 12; ++i)
    objects += R"(, {"type": "instance", "group": "g", "transform": {"rotate": [1,2,3,)" +
               std::to_string(30 * i) + R"(], "translate": )" +
               preciseVec(2 * rnd(4, i, 0) - 1, 2 * rnd(4, i, 1) - 1, 2 * rnd(4, i, 2) - 1) + "}}";
  objects += R"(, {"type": "instance", "group": "g", "motion": {"transform": [
      {"rotate": [0,0,1,0]}, {"rotate": [0,0,1,120], "translate": [0.5,0,0]}, {"rotate": [0,0,1,240]}]}},
    {"type": "sphere", "center": [0,0,0], "radius": 0.2, "material": "m",
     "motion": {"center": [[0,0,0], [0.5,0.5,0], [1,0,0]]}},
    {"type": "quad", "corner": [-1,-0.3,-1], "edge1": [2,0,0], "edge2": [0,0,2], "material": "m"},
    {"type": "box", "min": [-0.2,-0.2,-0.2], "max": [0.2,0.2,0.2], "material": "m"},
    {"type": "mesh", "material": "m", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]],
     "motion": {"positions": [[[0,0,0],[1,0,0],[0,1,0]], [[0,0,1],[1,0,0.5],[0,1,-0.5]]]}})";
  return sceneWith(objects, "\"g\": [" + soup(5, 40, 0.2f) + R"(,
      {"type": "sphere", "center": [0.3,0,0], "radius": 0.1, "material": "m"}])");
}

// `rays` random rays (a twentieth under AddressSanitizer) through Embree, the sphere hierarchy and
// brute force: hit/miss, primitive and occlusion agreement ≥ 1 − 10⁻⁶ (over ≤ 2·10⁵
// comparisons: none may differ), with ≥ 1 % of the comparisons hits in both so that t and the
// primitive are checked too; and the tree's invariants hold.
void expectAgreement(const std::string& text, const char* what, int rays = 100000) {
  const Scene s = test::sceneFromText(text);
  const EmbreeAccel embree(s);
  const SphereHierarchy tree(s);
  const BruteForce brute(s);
  const CrossCheck check(embree, {&tree, &brute});
  castRandomRays(s, check, test::agreementRays(rays), 17);
  const CrossCheckStats& st = check.stats();
  EXPECT_GE(st.relDt.size(), st.rays / 100) << what;
  EXPECT_GE(st.hitAgreement(), 1 - 1e-6) << what;
  EXPECT_GE(st.primAgreement(), 1 - 1e-6) << what;
  EXPECT_GE(st.occlusionAgreement(), 1 - 1e-6) << what;
  for (const auto& line : st.firstDisagreements) ADD_FAILURE() << what << ": " << line;
  EXPECT_EQ(tree.checkInvariants(), "") << what;
}

TEST(SphereHierarchy, TriangleSoupAgreesWithEmbreeAndBruteForce) {
  expectAgreement(sceneWith(soup(1, 600, 0.4f)), "soup", 30000);
}

TEST(SphereHierarchy, SpheresAgreeWithEmbreeAndBruteForce) {
  expectAgreement(sceneWith(spheres(2, 150)), "spheres");
}

TEST(SphereHierarchy, InstancesMotionAndEveryShapeAgreeWithEmbreeAndBruteForce) {
  // Fewer rays: brute force tests each of the ~900 primitives and instances on every one.
  expectAgreement(mixedScene(), "instances and motion", 20000);
}

TEST(SphereHierarchy, DegenerateTrianglesAgreeWithEmbreeAndBruteForce) {
  // A needle, collinear corners, a zero-height sliver and duplicated triangles: their spheres
  // have zero or tiny radius, which the padded sphere test must still let rays into.
  expectAgreement(sceneWith(R"(
    {"type": "mesh", "material": "m", "positions": [[0,0,0],[1,0,0],[0,0,0], [0,0,0],[1,1,1],[2,2,2]],
     "indices": [[0,1,2],[3,4,5]]},
    {"type": "mesh", "material": "m", "positions": [[-1,0.5,0],[1,0.5,0],[0,0.5,1e-20]], "indices": [[0,1,2]]},
    {"type": "mesh", "material": "m", "positions": [[-1,-1,-0.5],[1,-1,-0.5],[-1,1,-0.5]],
     "indices": [[0,1,2],[0,1,2]]})"),
                  "degenerate");
}

TEST(SphereHierarchy, TwoSpheresGetTheSmallestSphereAroundThem) {
  // Unit spheres at x = ±2: the smallest sphere around both is centred between them with radius
  // 3; the sphere around their box [−3, 3] × [−1, 1]² would have radius √11 ≈ 3.32. The build
  // rounds radii up by one float step (3 + 2.4e-7).
  const Scene s = test::sceneFromText(sceneWith(
      R"({"type": "sphere", "center": [-2,0,-5], "radius": 1, "material": "m"},
         {"type": "sphere", "center": [2,0,-5], "radius": 1, "material": "m"})"));
  const SphereHierarchy tree(s);
  const Sphere root = tree.rootSphere(0);
  EXPECT_NEAR(root.center.x, 0, 1e-6);
  EXPECT_NEAR(root.center.y, 0, 1e-6);
  EXPECT_NEAR(root.center.z, -5, 1e-6);
  EXPECT_NEAR(root.radius, 3, 1e-6);
  EXPECT_GE(root.radius, 3);
  EXPECT_EQ(tree.stats().nodes, 3u);  // a root over two leaves of one sphere each
  EXPECT_EQ(tree.checkInvariants(), "");
}

TEST(SphereHierarchy, ParentSpheresEncloseTheirChildrenOverALargeTree) {
  // 20 000 triangles: a tree about 13 levels deep, every enclosure checked node by node.
  const Scene s = test::sceneFromText(sceneWith(soup(7, 20000, 0.05f)));
  const SphereHierarchy tree(s);
  EXPECT_GE(tree.stats().maxDepth, 12u);  // ≥ log₂(20 000 / 4): the check walks a deep tree
  EXPECT_LE(tree.stats().maxDepth, SphereHierarchy::kMedianBelowDepth);
  EXPECT_EQ(tree.stats().primitives, 20000u);
  EXPECT_EQ(tree.checkInvariants(), "");
}

TEST(SphereHierarchy, RaysGrazingEveryBoundingSphereFindBruteForcesHit) {
  // For every sphere of the tree (node or primitive), rays tangent to it — touching it at a
  // point, or passing 2⁻²⁰ of its radius inside or outside — in random directions perpendicular
  // to the radius there: a sphere test that rounded towards a miss would drop a primitive
  // the ray does meet. Each triangle's farthest corner lies on its own sphere, so some of these
  // rays also graze a triangle's corner. Brute force has the hit.
  const Scene s = test::sceneFromText(sceneWith(soup(9, 200, 0.5f) + "," + spheres(8, 30)));
  const SphereHierarchy tree(s);
  const BruteForce brute(s);
  std::vector<Sphere> bounds;
  for (const auto& n : tree.tree(0).nodes) bounds.push_back(n.bound);
  for (const auto& slot : tree.tree(0).slots) bounds.push_back(slot.bound);
  int rays = 0, hits = 0;
  for (size_t i = 0; i < bounds.size(); ++i) {
    const Sphere& b = bounds[i];
    for (int k = 0; k < 6; ++k) {
      const auto u = [&](int j) {
        return toUnitFloat(hashKey(31, uint32_t(i * 6 + size_t(k)), j));
      };
      const float z = 1 - 2 * u(0), phi = 2 * kPi * u(1), st = std::sqrt(std::max(0.0f, 1 - z * z));
      const Vec3f n{st * std::cos(phi), st * std::sin(phi), z};
      // A direction perpendicular to n: n × a random vector.
      const Vec3f t = normalize(cross(n, Vec3f{u(2) - 0.5f, u(3) - 0.5f, u(4) - 0.5f}));
      const float offset = (k % 3 == 0 ? 0.0f : k % 3 == 1 ? 0x1p-20f : -0x1p-20f) * b.radius;
      const Vec3f touch = b.center + (b.radius + offset) * n;
      const Ray r{touch - 4 * std::max(b.radius, 0.1f) * t, t};
      const Hit a = tree.intersect(r), e = brute.intersect(r);
      ASSERT_EQ(bool(a), bool(e)) << "sphere " << i << " ray " << k;
      if (a) {
        EXPECT_EQ(a.t, e.t);
        EXPECT_EQ(a.geomId, e.geomId);
        EXPECT_EQ(a.primId, e.primId);
      }
      EXPECT_EQ(tree.occluded(r), brute.occluded(r)) << "sphere " << i << " ray " << k;
      ++rays;
      hits += bool(a);
    }
  }
  EXPECT_GT(hits, rays / 20);  // the rays pass through the geometry, not only beside it
}

TEST(SphereHierarchy, RaysTangentToALoneSphereAreNotDropped) {
  // A lone sphere is its tree's only bound (the root is its leaf, its sphere the object itself),
  // so a ray tangent to it meets a bounding-sphere test and the object test that round the same
  // quantities differently; wherever the object test finds a hit, the bound's must not have
  // rounded towards a miss. 20 000 rays tangent to the sphere (within a few float steps), near
  // the origin and 10⁴ units from it.
  for (const float far : {0.0f, 1e4f}) {
    SCOPED_TRACE(far);
    const Vec3f c{0.3f + far, 0.7f - far, -5.1f};
    const float radius = 0.9f;
    const Scene s =
        test::sceneFromText(sceneWith(R"({"type": "sphere", "material": "m", "center": )" +
                                      preciseVec(c.x, c.y, c.z) + ", \"radius\": 0.9}"));
    const SphereHierarchy tree(s);
    const BruteForce brute(s);
    int hits = 0;
    for (uint32_t i = 0; i < 20000; ++i) {
      const auto u = [&](int j) { return toUnitFloat(hashKey(33, i, j)); };
      const float z = 1 - 2 * u(0), phi = 2 * kPi * u(1), st = std::sqrt(std::max(0.0f, 1 - z * z));
      const Vec3f n{st * std::cos(phi), st * std::sin(phi), z};
      const Vec3f t = normalize(cross(n, Vec3f{u(2) - 0.5f, u(3) - 0.5f, u(4) - 0.5f}));
      // Half from 10 radii away, half from 10⁴: there a discriminant formed as b² − ac would
      // lose every digit to cancellation (Ray Tracing Gems ch. 7).
      const float back = (i % 2 ? 10.0f : 1e4f) * radius;
      const Ray r{c + radius * n - back * t, t};
      const Hit a = tree.intersect(r), e = brute.intersect(r);
      ASSERT_EQ(bool(a), bool(e)) << "ray " << i;
      if (a) {
        EXPECT_EQ(a.t, e.t);
      }
      hits += bool(e);
    }
    // Tangent to within rounding: both answers occur, so the rays do sit on the edge.
    EXPECT_GT(hits, 1000);
    EXPECT_LT(hits, 19000);
  }
}

}  // namespace
}  // namespace glint
