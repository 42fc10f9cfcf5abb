// The reference BVH against Embree and the brute-force oracle on generated scenes, plus the
// watertightness, slab and tree-invariant cases of the reference-BVH issue.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "accel/brute_force.h"
#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/reference_bvh.h"
#include "accel/soup_scenes.h"
#include "core/hash.h"
#include "test_util.h"

namespace glint {
namespace {

using test::preciseVec;
using test::rnd;
using test::sceneWith;
using test::soup;

struct Agreement {
  CrossCheckStats stats;
  std::string invariants;
};

Agreement crossCheck(const std::string& text, int rays, BvhSplit split = BvhSplit::Sah) {
  const Scene s = test::sceneFromText(text);
  const EmbreeAccel embree(s);
  const ReferenceBvh bvh(s, split);
  const BruteForce brute(s);
  const CrossCheck check(embree, {&bvh, &brute});
  castRandomRays(s, check, test::agreementRays(rays), 17);
  return {check.stats(), bvh.checkInvariants()};
}

void expectAgreement(const Agreement& a, const char* what) {
  // 1e5 random rays (a twentieth under AddressSanitizer; two backends each): hit/miss agreement
  // must be at least 1 − 1e-6, which over ≤ 2·10⁵ comparisons means no disagreement at all.
  // The rays start inside the scene's bounds, so many meet geometry; fewer than 1 % of the
  // comparisons with both backends hitting would leave the t and primitive checks nearly empty.
  EXPECT_GE(a.stats.relDt.size(), a.stats.rays / 100) << what;
  EXPECT_GE(a.stats.hitAgreement(), 1 - 1e-6) << what;
  EXPECT_GE(a.stats.primAgreement(), 1 - 1e-6) << what;
  EXPECT_GE(a.stats.occlusionAgreement(), 1 - 1e-6) << what;
  EXPECT_LE(a.stats.quantileRelDt(0.999), 1e-5) << what;
  for (const auto& line : a.stats.firstDisagreements) ADD_FAILURE() << what << ": " << line;
  EXPECT_EQ(a.invariants, "") << what;
}

TEST(ReferenceBvh, TriangleSoup) {
  expectAgreement(crossCheck(sceneWith(soup(1, 600, 0.4f)), 100000), "soup");
}

TEST(ReferenceBvh, Spheres) {
  std::string objects;
  for (int i = 0; i < 150; ++i)
    objects += (i ? "," : "") + std::string(R"({"type": "sphere", "material": "m", "center": )") +
               preciseVec(2 * rnd(2, i, 0) - 1, 2 * rnd(2, i, 1) - 1, 2 * rnd(2, i, 2) - 1) +
               ", \"radius\": " + std::to_string(0.01 + 0.1 * rnd(2, i, 3)) + "}";
  expectAgreement(crossCheck(sceneWith(objects), 100000), "spheres");
}

TEST(ReferenceBvh, DegenerateNeedleFlatAndCoincidentTriangles) {
  const std::string objects = R"(
    {"type": "mesh", "material": "m", "positions": [[0,0,0],[1,0,0],[0,0,0], [0,0,0],[1,1,1],[2,2,2]],
     "indices": [[0,1,2],[3,4,5]]},
    {"type": "mesh", "material": "m", "positions": [[-1,0.5,0],[1,0.5,0],[0,0.5,1e-20]], "indices": [[0,1,2]]},
    {"type": "mesh", "material": "m", "positions": [[-1,-1,0.25],[1,-1,0.25],[-1,1,0.25],[1,1,0.25]],
     "indices": [[0,1,2],[1,3,2]]},
    {"type": "mesh", "material": "m", "positions": [[-1,-1,-0.5],[1,-1,-0.5],[-1,1,-0.5]],
     "indices": [[0,1,2],[0,1,2]]},
    {"type": "quad", "corner": [-1,-0.3,-1], "edge1": [2,0,0], "edge2": [0,0,2], "material": "m"},
    {"type": "box", "min": [-0.2,-0.2,-0.2], "max": [0.2,0.2,0.2], "material": "m"})";
  expectAgreement(crossCheck(sceneWith(objects), 100000), "degenerate");
}

TEST(ReferenceBvh, InstancesAndMotion) {
  std::string objects = soup(3, 100, 0.3f);
  for (int i = 0; i < 12; ++i)
    objects += R"(, {"type": "instance", "group": "g", "transform": {"rotate": [1,2,3,)" +
               std::to_string(30 * i) + R"(], "translate": )" +
               preciseVec(2 * rnd(4, i, 0) - 1, 2 * rnd(4, i, 1) - 1, 2 * rnd(4, i, 2) - 1) + "}}";
  objects += R"(, {"type": "instance", "group": "g", "motion": {"transform": [
      {"rotate": [0,0,1,0]}, {"rotate": [0,0,1,120], "translate": [0.5,0,0]}, {"rotate": [0,0,1,240]}]}},
    {"type": "sphere", "center": [0,0,0], "radius": 0.2, "material": "m",
     "motion": {"center": [[0,0,0], [0.5,0.5,0], [1,0,0]]}},
    {"type": "mesh", "material": "m", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]],
     "motion": {"positions": [[[0,0,0],[1,0,0],[0,1,0]], [[0,0,1],[1,0,0.5],[0,1,-0.5]]]}})";
  expectAgreement(crossCheck(sceneWith(objects, "\"g\": [" + soup(5, 40, 0.2f) + R"(,
      {"type": "sphere", "center": [0.3,0,0], "radius": 0.1, "material": "m"}])"),
                             100000),
                  "instances and motion");
}

TEST(ReferenceBvh, MedianAndMidpointBuildsAgreeToo) {
  for (BvhSplit split : {BvhSplit::Median, BvhSplit::Midpoint}) {
    const Agreement a = crossCheck(sceneWith(soup(6, 300, 0.3f)), 50000, split);
    EXPECT_EQ(a.stats.hitAgree, a.stats.rays) << bvhSplitName(split);
    EXPECT_EQ(a.invariants, "") << bvhSplitName(split);
  }
}

// A closed icosphere: the icosahedron subdivided twice, vertices pushed onto the unit sphere.
TriangleMesh icosphere() {
  const float t = (1 + std::sqrt(5.0f)) / 2;
  std::vector<Vec3f> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<uint32_t> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                             4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                             6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (auto& p : v) p = normalize(p);
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mids;
    const auto mid = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mids.find(key);
      if (it != mids.end()) return it->second;
      v.push_back(normalize(v[a] + v[b]));
      return mids[key] = static_cast<uint32_t>(v.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < f.size(); i += 3) {
      const uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = next;
  }
  TriangleMesh m;
  m.positions = v;
  m.indices = f;
  return m;
}

std::string meshJson(const TriangleMesh& m) {
  std::string pos, idx;
  for (const Vec3f& p : m.positions) pos += (pos.empty() ? "" : ",") + preciseVec(p.x, p.y, p.z);
  for (size_t i = 0; i < m.indices.size(); i += 3)
    idx += (idx.empty() ? "[" : ",[") + std::to_string(m.indices[i]) + "," +
           std::to_string(m.indices[i + 1]) + "," + std::to_string(m.indices[i + 2]) + "]";
  return R"({"type": "mesh", "material": "m", "positions": [)" + pos + "], \"indices\": [" + idx +
         "]}";
}

TEST(ReferenceBvh, RaysAtVerticesAndEdgesOfAClosedMeshNeverMiss) {
  // Watertightness (Woop et al. 2013): a ray aimed exactly at a vertex or along an edge is shared
  // by several triangles; at least one of them must report the hit.
  const TriangleMesh ico = icosphere();
  const Scene s = test::sceneFromText(sceneWith(meshJson(ico)));
  const ReferenceBvh bvh(s);
  std::vector<Vec3f> targets = s.meshes[0].positions;
  const TriangleMesh& m = s.meshes[0];
  for (size_t i = 0; i < m.indices.size(); i += 3)
    for (int e = 0; e < 3; ++e) {
      const Vec3f a = m.positions[m.indices[i + size_t(e)]];
      const Vec3f b = m.positions[m.indices[i + size_t((e + 1) % 3)]];
      targets.push_back(0.5f * (a + b));
      targets.push_back(0.25f * a + 0.75f * b);
    }
  int misses = 0;
  for (size_t i = 0; i < targets.size(); ++i) {
    // From outside, towards the target, from a spread of directions.
    const Vec3f from = 3.0f * normalize(targets[i] + Vec3f{0.3f * rnd(7, int(i), 0) - 0.15f,
                                                           0.3f * rnd(7, int(i), 1) - 0.15f, 0});
    misses += !bvh.intersect(Ray{from, targets[i] - from});
  }
  EXPECT_EQ(misses, 0) << "of " << targets.size() << " rays";
  // The icosahedron subdivided twice: 20·4² triangles on 10·4² + 2 vertices, kept as given.
  EXPECT_EQ(m.triangleCount(), 320u);
  EXPECT_EQ(m.positions.size(), 162u);
}

TEST(ReferenceBvh, RaysFromInsideAClosedMeshCrossAnOddNumberOfTimes) {
  // Counted with repeated closest-hit queries, each starting at the last t (the open interval
  // (t, ∞) skips a second triangle reporting the same crossing at an edge).
  const Scene s = test::sceneFromText(sceneWith(meshJson(icosphere())));
  const ReferenceBvh bvh(s);
  for (int i = 0; i < 5000; ++i) {
    Ray r;
    r.o = 0.5f * Vec3f{rnd(8, i, 0) - 0.5f, rnd(8, i, 1) - 0.5f, rnd(8, i, 2) - 0.5f};
    const float z = 1 - 2 * rnd(8, i, 3), phi = 2 * kPi * rnd(8, i, 4);
    r.d = {std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z};
    int crossings = 0;
    for (Hit h = bvh.intersect(r); h && crossings < 10; h = bvh.intersect(r)) {
      ++crossings;
      r.tMin = h.t;
    }
    EXPECT_EQ(crossings % 2, 1) << "ray " << formatRay(r);
  }
}

TEST(ReferenceBvh, SlabTestWithZeroDirectionAndOriginOnASlabPlane) {
  // The box [0,1]³: rays with a ±0 direction component whose origin lies exactly on that
  // component's slab plane (0·∞ = NaN in a naive slab test). No NaN, same answer as brute force.
  const Scene s = test::sceneFromText(sceneWith(
      R"({"type": "box", "min": [0,0,0], "max": [1,1,1], "material": "m"},
         {"type": "sphere", "center": [3,3,3], "radius": 0.1, "material": "m"})"));
  const ReferenceBvh bvh(s);
  const BruteForce brute(s);
  const std::vector<Ray> rays = {{{0, 0.5f, -1}, {0.0f, 0, 1}}, {{0, 0.5f, -1}, {-0.0f, 0, 1}},
                                 {{1, 0.5f, -1}, {0.0f, 0, 1}}, {{0.5f, 1, -1}, {0, -0.0f, 1}},
                                 {{0.5f, 0.5f, 0}, {0, 0, 1}},  {{0, 0, -1}, {0.0f, -0.0f, 1}},
                                 {{1, 1, 2}, {0.0f, 0.0f, -1}}, {{-1, 0, 0}, {1, 0.0f, 0.0f}}};
  for (const Ray& r : rays) {
    const Hit a = bvh.intersect(r), b = brute.intersect(r);
    EXPECT_EQ(bool(a), bool(b)) << formatRay(r);
    if (a && b) {
      EXPECT_TRUE(std::isfinite(a.t)) << formatRay(r);
      EXPECT_EQ(a.t, b.t) << formatRay(r);
    }
    EXPECT_EQ(bvh.occluded(r), bool(b)) << formatRay(r);
  }
}

TEST(ReferenceBvh, TreeInvariantsAndStatistics) {
  const Scene s = test::sceneFromText(sceneWith(soup(9, 5000, 0.05f)));
  for (BvhSplit split : {BvhSplit::Sah, BvhSplit::Median, BvhSplit::Midpoint}) {
    const ReferenceBvh bvh(s, split);
    EXPECT_EQ(bvh.checkInvariants(), "") << bvhSplitName(split);
    EXPECT_EQ(bvh.stats().primitives, 5000u);
    EXPECT_EQ(bvh.stats().nodes, 2 * bvh.stats().leaves - 1);  // a full binary tree
    EXPECT_LE(bvh.stats().primitivesPerLeaf(), ReferenceBvh::kMaxLeafSize);
  }
  // SAH exists to beat the simple splits on its own cost measure.
  EXPECT_LT(ReferenceBvh(s, BvhSplit::Sah).stats().sahCost,
            ReferenceBvh(s, BvhSplit::Median).stats().sahCost);
}

}  // namespace
}  // namespace glint
