// Motion blur (seed 000 §13.4.5): keys spread evenly over normalised time [0, 1], the shutter
// selecting when the camera is open.
#include <gtest/gtest.h>

#include <optional>

#include "core/hash.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

Film render(const std::string& text, AccelKind kind = AccelKind::Embree,
            std::optional<PixelWindow> crop = std::nullopt) {
  const Scene s = test::sceneFromText(text);
  const auto accel = makeAccelerator(kind, s);
  RenderOptions opt;
  opt.progress = false;
  opt.crop = crop;
  return renderScene(s, *accel, opt).film;
}

// Three standard deviations of a coverage estimate p from n samples, treating each sample as a
// Bernoulli trial: pairing stratified pixel and time samples does not reduce the variance of
// the coverage indicator much, since it is not additive in the two.
double threeSigma(double p, int n) { return 3 * std::sqrt(std::max(p * (1 - p), 1.0 / n) / n); }

const char* kCommon = R"(
  "render": {"width": 32, "height": 24, "spp": 4, "background": [0.1,0.2,0.3]},
  "materials": {"m": {"type": "phong", "kd": [0.8,0.5,0.3], "ks": [0.3,0.3,0.3]}},
  "lights": [{"type": "point", "position": [2,4,5]}],)";

std::string scene(const std::string& shutter, const std::string& objects) {
  return std::string("{") + kCommon + R"("camera": {"eye": [0,1,6], "look_at": [0,0.5,0],
      "shutter": )" +
         shutter + R"(}, "objects": [)" + objects + "]}";
}

TEST(Motion, ClosedShutterIsTheStaticImageAtThatTime) {
  // At t = 0.5 the centre keys (0,0.5,0) → (2,0.5,0) interpolate to exactly (1,0.5,0), and the
  // mesh keys to exactly their midpoint: the same bytes as the static scene.
  const std::string moving = scene("[0.5, 0.5]", R"(
    {"type": "sphere", "center": [0,0.5,0], "radius": 0.5, "material": "m",
     "motion": {"center": [[0,0.5,0], [2,0.5,0]]}},
    {"type": "mesh", "positions": [[-2,0,0],[-1,0,0],[-2,1,0]], "indices": [[0,1,2]], "material": "m",
     "motion": {"positions": [[[-2,0,0],[-1,0,0],[-2,1,0]], [[-2,0,-1],[-1,0,-1],[-2,2,-1]]]}})");
  const std::string still = scene("[0, 0]", R"(
    {"type": "sphere", "center": [1,0.5,0], "radius": 0.5, "material": "m"},
    {"type": "mesh", "positions": [[-2,0,-0.5],[-1,0,-0.5],[-2,1.5,-0.5]], "indices": [[0,1,2]], "material": "m"})");
  EXPECT_EQ(render(moving).toFloatRgba(), render(still).toFloatRgba());
  // At the keys themselves (t = 0 and t = 1) too.
  EXPECT_EQ(render(scene("[1, 1]", R"({"type": "sphere", "center": [0,0.5,0], "radius": 0.5,
              "material": "m", "motion": {"center": [[0,0.5,0], [2,0.5,0]]}})"))
                .toFloatRgba(),
            render(scene("[0, 0]", R"({"type": "sphere", "center": [2,0.5,0], "radius": 0.5,
              "material": "m"})"))
                .toFloatRgba());
}

// Coverage (alpha) of an orthographic 64 × 1 strip 4 units wide (16 px per unit), 1/16 tall.
Film strip(const std::string& objects, int spp) {
  return render(R"({"render": {"width": 64, "height": 1, "spp": )" + std::to_string(spp) +
                R"(, "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 0.0625,
               "shutter": [0, 1]},
    "materials": {"m": {"type": "phong"}}, "objects": [)" +
                objects + "]}");
}

TEST(Motion, MovingSphereLeavesTheProjectedCoverageRamp) {
  // Radius r = 0.5 moving x: −1 → 1. A point u is covered while |u − c(t)| < r, i.e. for the
  // part of [−1, 1] that [u − r, u + r] overlaps: coverage(u) = overlap / 2. The strip is 1/16
  // tall, so the disk's half-width there is within 1e-3 of r. Coverage is linear in u across
  // each pixel (its kinks fall on pixel edges), so the pixel average is the value at its centre.
  constexpr int kSpp = 4096;
  const Film f = strip(R"({"type": "sphere", "center": [-1,0,0], "radius": 0.5, "material": "m",
      "motion": {"center": [[-1,0,0], [1,0,0]]}})",
                       kSpp);
  for (int x = 0; x < 64; ++x) {
    const double u = -2 + (x + 0.5) / 16.0;
    const double overlap = std::max(0.0, std::min(u + 0.5, 1.0) - std::max(u - 0.5, -1.0));
    EXPECT_NEAR(f.pixel(x, 0)[3], overlap / 2, threeSigma(overlap / 2, kSpp)) << "u = " << u;
  }
}

TEST(Motion, RotatingInstanceBlursAlongItsArc) {
  // A sphere of radius 0.1 at distance 1 from the z axis, rotated 0° → 90° about z across the
  // shutter by quaternion keys: it sweeps a quarter circle. A point p is covered for the part of
  // the arc where |p − (cosθ, sinθ, 0)| < 0.1. Linear matrix interpolation would cut the chord
  // instead and leave the arc's middle (45°) uncovered.
  constexpr int kSpp = 4096;
  const std::string text = R"({"render": {"width": 128, "height": 128, "spp": 4096,
                                          "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 2.4,
               "shutter": [0, 1]},
    "materials": {"m": {"type": "phong"}},
    "groups": {"ball": [{"type": "sphere", "center": [1,0,0], "radius": 0.1, "material": "m"}]},
    "objects": [{"type": "instance", "group": "ball",
                 "motion": {"transform": [{"rotate": [0,0,1,0]}, {"rotate": [0,0,1,90]}]}}]})";
  // Only the pixels under test are rendered (crops give the same values as a full render).
  const auto coverageAt = [&](int x, int y) {
    return render(text, AccelKind::Embree, PixelWindow{x, x + 1, y, y + 1}).pixel(x, y)[3];
  };
  const auto expectedCoverage = [](int x, int y) {
    // Averaged over a 4 × 4 grid in the pixel, each point over 2000 steps of θ.
    double sum = 0;
    for (int sy = 0; sy < 4; ++sy)
      for (int sx = 0; sx < 4; ++sx) {
        const double u = -1.2 + (x + (sx + 0.5) / 4) * 2.4 / 128;
        const double v = 1.2 - (y + (sy + 0.5) / 4) * 2.4 / 128;
        int covered = 0;
        for (int k = 0; k < 2000; ++k) {
          const double th = (k + 0.5) / 2000 * kPi / 2;
          covered += std::hypot(u - std::cos(th), v - std::sin(th)) < 0.1;
        }
        sum += covered / 2000.0;
      }
    return sum / 16;
  };
  // Along the arc at 10°, 45° and 80°, and off it (at −20° and at the centre).
  for (double deg : {10.0, 45.0, 80.0, -20.0}) {
    const double th = deg * kPi / 180;
    const int x = static_cast<int>((std::cos(th) + 1.2) / 2.4 * 128);
    const int y = static_cast<int>((1.2 - std::sin(th)) / 2.4 * 128);
    const double expected = expectedCoverage(x, y);
    // + 2e-3 for the quadrature of the expected value itself.
    EXPECT_NEAR(coverageAt(x, y), expected, threeSigma(expected, kSpp) + 2e-3) << deg << "°";
  }
  EXPECT_GT(coverageAt(101, 26), 0.1);  // the 45° point really is covered (≈ 0.127)
  EXPECT_EQ(coverageAt(64, 64), 0.0);
}

TEST(Motion, BackendsAgreeOnMovingGeometry) {
  // Embree's time steps and the brute-force oracle's interpolation must give the same image.
  const std::string s = scene("[0, 1]", R"(
    {"type": "sphere", "center": [0,0.5,0], "radius": 0.5, "material": "m",
     "motion": {"center": [[0,0.5,0], [1,0.7,0], [2,0.5,0]]}},
    {"type": "box", "min": [-2,0,-1], "max": [-1,1,0], "material": "m",
     "motion": {"transform": [{"rotate": [0,1,0,0]}, {"rotate": [0,1,0,60], "translate": [0,0.3,0]}]}})");
  const Film a = render(s, AccelKind::Embree), b = render(s, AccelKind::BruteForce);
  int differing = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 4; ++c)
        differing += std::fabs(a.pixel(x, y)[c] - b.pixel(x, y)[c]) > 1e-4;
  // Triangle hits differ in the last bits between Embree and the watertight test, and Embree's
  // slerp turns the box by up to ~7e-5 rad more or less than ours (kSlerpAngleError, 2e-4, bounds
  // it): a face's normal, and so a Lambert value under unit light, moves by at most that, below
  // the 1e-4 allowed. A sample can flip at a silhouette only where a ray grazes an edge: allow
  // none over a 768-pixel image.
  EXPECT_EQ(differing, 0);
}

TEST(Motion, ATurningObjectDoesNotShadowItself) {
  // A slab turning 3.9° about y with a light straight in front of its long face: every shadow
  // ray from that face must reach the light. Embree interpolates the rotation with a fast acos
  // whose error (up to ~7e-5 rad here) turns its copy of the slab slightly differently from ours;
  // before Scene::shadingPoint widened the error bound by kSlerpAngleError, 3018 of these rays (15
  // %) were blocked by the slab itself.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,4,6], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "box", "min": [-1.5,-0.1,-0.3], "max": [1.5,0.1,0.3], "material": "m",
                 "motion": {"transform": [{"rotate": [0,1,0,0]}, {"rotate": [0,1,0,3.9]}]}}]})");
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  const Vec3f light = toFloat(Vec3d{0, 0, 50} - s.worldOrigin);
  int tops = 0, blocked = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(17, i, k)); };
    Ray r;
    r.o = toFloat(Vec3d{2.8 * u(0) - 1.4, 0.18 * u(1) - 0.09, 2} - s.worldOrigin);
    r.d = {0, 0, -1};
    r.time = u(2);
    const Hit h = embree->intersect(r);
    if (!h) continue;
    const ShadingPoint sp = s.shadingPoint(r, h);
    if (sp.ng.z < 0.99f) continue;  // the long face only
    ++tops;
    blocked += embree->occluded(spawnRayTo(sp, light, r.time));
  }
  EXPECT_GT(tops, 15000);
  EXPECT_EQ(blocked, 0);
}

}  // namespace
}  // namespace glint
