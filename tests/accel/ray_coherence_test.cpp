// Ray coherence (seed 002 §9.2.4): the visibility sets against hand-computed ones, the query
// rules on rays that carry an origin, its bounded preprocessing, and its hits against Embree's
// on every bundled scene, for random rays, rays from origins and a render's own rays.
#include "accel/ray_coherence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "accel/cross_check.h"
#include "accel/embree_accel.h"
#include "accel/origin_rays.h"
#include "accel/triangle_scenes.h"
#include "io/scene_loader.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// The face of the direction cube and its (u, v) for a direction whose largest component is +z.
// A block of ±1e-6 around it spans about 10⁻⁶ rad: far inside 0.1°.
bool mayMeetNear(const VisibilitySet& set, const Vec3f& d) {
  const DirectionClasses classes(16);
  const double u = d.x / d.z, v = d.y / d.z, w = 1e-6;
  return classes.mayMeet(set, 4, u - w, u + w, v - w, v + w);
}

Vec3f tilted(double degrees, double azimuth = 0) {
  const double t = degrees * kDegree;
  return {float(std::sin(t) * std::cos(azimuth)), float(std::sin(t) * std::sin(azimuth)),
          float(std::cos(t))};
}

TEST(VisibilitySets, SpherePairIsTheCircleOfArcsinOfTheRadiiOverTheDistance) {
  // c1 = 0, r1 = 1; c2 = (0, 0, 10), r2 = 4: half-angle arcsin((1 + 4)/10) = 30°.
  const VisibilitySet set =
      visibilitySet(Shell::ofSphere({0, 0, 0}, 1), Shell::ofSphere({0, 0, 10}, 4), 0);
  ASSERT_FALSE(set.everywhere);
  EXPECT_NEAR(set.halfAngle, 30 * kDegree + kAnglePad, 1e-12);
  EXPECT_NEAR(set.axis.z, 1, 1e-12);
  for (double azimuth : {0.0, 1.0, 2.5, 4.0}) {
    EXPECT_TRUE(mayMeetNear(set, tilted(29.9, azimuth))) << azimuth;
    EXPECT_FALSE(mayMeetNear(set, tilted(30.1, azimuth))) << azimuth;
  }
  // Every class holding a direction of the cone is listed.
  const DirectionClasses classes(16);
  std::vector<bool> listed(classes.count());
  classes.forEachClassMeeting(set, [&](uint32_t c) { listed[c] = true; });
  for (int k = 0; k < 64; ++k) EXPECT_TRUE(listed[classes.classOf(tilted(29.9, k * 0.1))]);
  // Overlapping spheres (|c1 − c2| = 4 < 1 + 4) see each other in every direction.
  EXPECT_TRUE(
      visibilitySet(Shell::ofSphere({0, 0, 0}, 1), Shell::ofSphere({0, 0, 4}, 4), 0).everywhere);
}

TEST(VisibilitySets, ConvexPolytopesAreTheHullOfTheVertexPairDirections) {
  // From the point 0 to the square [−1, 1]² at z = 10: the pyramid whose sides lean
  // atan(1/10) = 5.711° from z along x and y, and atan(√2/10) = 8.050° along the diagonals.
  const VisibilitySet square =
      visibilitySet(Shell::ofSphere({0, 0, 0}, 0),
                    Shell::ofPolygon({{-1, -1, 10}, {1, -1, 10}, {1, 1, 10}, {-1, 1, 10}}), 0);
  ASSERT_FALSE(square.everywhere);
  EXPECT_EQ(square.generators.size(), 4u);
  for (double azimuth : {0.0, 0.5, 1.0, 1.5}) {
    EXPECT_TRUE(mayMeetNear(square, tilted(5.65, azimuth * std::numbers::pi))) << azimuth;
    EXPECT_FALSE(mayMeetNear(square, tilted(5.77, azimuth * std::numbers::pi))) << azimuth;
  }
  EXPECT_TRUE(mayMeetNear(square, tilted(8.0, std::numbers::pi / 4)));
  EXPECT_FALSE(mayMeetNear(square, tilted(8.1, std::numbers::pi / 4)));
  // Box [−1, 1]³ to box [−1, 1]² × [9, 11]: the difference is [−2, 2]² × [8, 12], whose
  // directions lean atan(2/8) = 14.036° along x and atan(2√2/8) = 19.471° along the diagonal.
  const VisibilitySet boxes = visibilitySet(Shell::ofBox({{-1, -1, -1}, {1, 1, 1}}),
                                            Shell::ofBox({{-1, -1, 9}, {1, 1, 11}}), 0);
  ASSERT_FALSE(boxes.everywhere);
  EXPECT_TRUE(mayMeetNear(boxes, tilted(13.95)));
  EXPECT_FALSE(mayMeetNear(boxes, tilted(14.1)));
  EXPECT_TRUE(mayMeetNear(boxes, tilted(19.4, std::numbers::pi / 4)));
  EXPECT_FALSE(mayMeetNear(boxes, tilted(19.55, std::numbers::pi / 4)));
  // Boxes that touch along every axis may hold 0 in their difference: every direction.
  EXPECT_TRUE(visibilitySet(Shell::ofBox({{0, 0, 0}, {1, 1, 1}}),
                            Shell::ofBox({{1, 0.5f, 0.5f}, {2, 2, 2}}), 0)
                  .everywhere);
}

// A mirror sphere at 0 (r = 1) and a diffuse one at (0, 0, 10) (r = 4); the eye at (0, 0, −20).
Scene twoSpheres() {
  return test::sceneFromText(R"({"camera": {"eye": [0,0,-20], "look_at": [0,0,0]},
    "materials": {"mirror": {"type": "mirror"}, "m": {"type": "phong"}},
    "lights": [{"type": "point", "position": [0, 30, 0]}],
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "mirror"},
                {"type": "sphere", "center": [0,0,10], "radius": 4, "material": "m"}]})");
}

TEST(RayCoherence, ListsFollowTheVisibilitySetsAndCheckTheOrigin) {
  const Scene s = twoSpheres();
  const RayCoherence rc(s, 64);
  // Origins: the eye, the point light, the mirror.
  EXPECT_EQ(rc.stats().origins, 3u);
  EXPECT_EQ(rc.stats().rows, 3u);
  // Render space is world space less the eye (io/placement.h).
  const Vec3f eye = toFloat(s.worldOrigin), mirrorTop = Vec3f{0, 0, 1} - eye;
  Ray r;
  r.o = mirrorTop;
  r.origin = 0;  // the mirror's world entry
  bool reversed = true;
  // A class of resolution 64 spans under 1.3° at 30° from z, so 27° is listed and 33° is not.
  r.d = tilted(27);
  const int row = rc.rowOf(r, reversed);
  ASSERT_GE(row, 0);
  EXPECT_FALSE(reversed);
  const auto near = rc.list(row, rc.classes().classOf(r.d));
  EXPECT_NE(std::find(near.begin(), near.end(), 1u), near.end());
  const auto past = rc.list(row, rc.classes().classOf(tilted(33)));
  EXPECT_EQ(std::find(past.begin(), past.end(), 1u), past.end());
  // The same tag on a ray that does not start on the mirror takes the fallback.
  r.o = Vec3f{0, 0, 2} - eye;
  EXPECT_LT(rc.rowOf(r, reversed), 0);
  // No tag, or the tag of the diffuse sphere (no row): the fallback.
  r.o = mirrorTop;
  r.origin = ray_origin::kNone;
  EXPECT_LT(rc.rowOf(r, reversed), 0);
  r.origin = 1;
  EXPECT_LT(rc.rowOf(r, reversed), 0);
  // A shadow segment towards the light is classified from the light, reversed; one that runs
  // past the light (tMax > 1) or ends elsewhere takes the fallback.
  const Vec3f light = Vec3f{0, 30, 0} - eye;
  r.o = mirrorTop;
  r.d = light - r.o;
  r.tMax = 1 - 1.0f / 4096;
  r.origin = ray_origin::light(0);
  EXPECT_GE(rc.rowOf(r, reversed), 0);
  EXPECT_TRUE(reversed);
  r.tMax = 2;
  EXPECT_LT(rc.rowOf(r, reversed), 0);
  r.tMax = 0.5f;
  r.d = 0.5f * r.d;
  EXPECT_LT(rc.rowOf(r, reversed), 0);
}

// Embree against ray coherence on random rays (no origin: the fallback), on rays that carry
// their origin (castOriginRays), and on the rays of a small render (camera, mirror, glass and
// shadow rays, each with its origin).
void expectAgreesWithEmbree(const Scene& scene, const std::string& what) {
  SCOPED_TRACE(what);
  const EmbreeAccel embree(scene);
  const RayCoherence coherence(scene);
  const CrossCheck check(embree, {&coherence});
  castRandomRays(scene, check, 20000, 3);
  castOriginRays(scene, embree, check, 20000, 4);
  Scene small = scene;
  small.render.width = 40;
  small.render.height = 30;
  small.render.spp = 1;
  RenderOptions opt;
  opt.threads = 1;
  opt.progress = false;
  renderScene(small, check, opt);
  const CrossCheckStats& st = check.stats();
  EXPECT_GE(st.hitAgreement(), 1 - 1e-6);
  EXPECT_GE(st.occlusionAgreement(), 1 - 1e-6);
  EXPECT_LE(double(st.originTies), 1e-4 * double(st.rays + st.occlusionRays));
  for (const auto& line : st.firstDisagreements) ADD_FAILURE() << line;
}

TEST(RayCoherence, AgreesWithEmbreeOnEveryBundledScene) {
  for (const std::string& name : test::fileNamesIn(GLINT_SCENES_DIR))
    if (name.ends_with(".json"))
      expectAgreesWithEmbree(loadSceneFile(std::string(GLINT_SCENES_DIR) + "/" + name), name);
}

// The rows a ray from an origin uses: the render's own rays must mostly find one, or the
// backend would be the fallback under another name.
TEST(RayCoherence, ARendersRaysUseTheirOriginsRows) {
  const Scene s = twoSpheres();
  const RayCoherence rc(s);
  const Camera cam(s.cameraDesc, 32, 32);
  int classified = 0;
  bool reversed = false;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      classified += rc.rowOf(cam.generateRay(float(x) + 0.5f, float(y) + 0.5f), reversed) >= 0;
  EXPECT_EQ(classified, 32 * 32);
}

// Many mirror spheres: every sphere is an origin, and m·n visibility sets would be 4·10⁸. The
// budgets bound the rows: ⌊pairs / n⌋ of them, the eye's and the light's first, and the rest of
// the origins' rays take the fallback, which still finds every hit.
TEST(RayCoherence, PreprocessingStaysWithinItsBudgets) {
  std::string objects;
  for (int i = 0; i < 20000; ++i)
    objects +=
        std::string(objects.empty() ? "" : ",") +
        R"({"type": "sphere", "radius": 0.05, "material": "mirror", "center": )" +
        test::vec(float(i % 40) * 0.2f, float(i / 40 % 25) * 0.2f, float(i / 1000) * 0.2f - 10) +
        "}";
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [4,2.5,10], "look_at": [4,2.5,0]},
    "materials": {"mirror": {"type": "mirror"}},
    "lights": [{"type": "point", "position": [0, 30, 0]}], "objects": [)" +
                                      objects + "]}");
  const RayCoherence rc(s, 8, 100000, 1 << 20);
  EXPECT_EQ(rc.stats().origins, 20002u);
  EXPECT_EQ(rc.stats().rows, 5u);  // ⌊10⁵ / 20 000⌋
  EXPECT_LE(rc.stats().pairs, 100000u);
  EXPECT_LE(2 * rc.stats().references + rc.stats().rows * (rc.stats().classes + 1), size_t(1)
                                                                                        << 20);
  // A word budget below one row's offsets leaves every origin without a row.
  EXPECT_EQ(RayCoherence(s, 8, 100000, 100).stats().rows, 0u);
  const EmbreeAccel embree(s);
  const CrossCheck check(embree, {&rc});
  castOriginRays(s, embree, check, 4000, 9);
  EXPECT_EQ(check.stats().hitAgree, check.stats().rays);
  EXPECT_EQ(check.stats().occlusionAgree, check.stats().occlusionRays);
}

// Counting the traversal (the study's objects tested per ray) changes no hit, on rays with and
// without origins.
TEST(RayCoherence, CountingChangesNoHit) {
  const Scene s = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/whitted.json");
  const RayCoherence rc(s);
  const Camera cam(s.cameraDesc, 64, 48);
  TraversalCounts counts;
  int hits = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      Ray r = cam.generateRay(float(x) + 0.5f, float(y) + 0.5f);
      for (uint32_t origin : {ray_origin::kEye, ray_origin::kNone}) {
        r.origin = origin;
        const Hit a = rc.intersect(r), b = rc.intersectCounting(r, counts);
        ASSERT_EQ(a.t, b.t);
        ASSERT_EQ(a.geomId, b.geomId);
        ASSERT_EQ(a.primId, b.primId);
        hits += bool(a);
      }
    }
  EXPECT_GT(hits, 0);
  EXPECT_GT(counts.tests, 0u);
}

}  // namespace
}  // namespace glint
