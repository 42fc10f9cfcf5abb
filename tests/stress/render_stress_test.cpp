// Stress cases through whole renders: energy, nested media, tiny lights, lenses, motion,
// recursion limits, runtime NaN and I/O faults.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "stress_util.h"

namespace glint {
namespace {

using stress::num;
using stress::vec;

// 9. Dielectric furnace: a non-absorbing glass sphere in a background of radiance 1, no
// lights, max_depth 64. Guards: energy created by Fresnel/refraction bookkeeping. Criterion:
// every pixel ≤ 1 + 1e-4.
TEST(Furnace, GlassSphereNeverExceedsTheBackground) {
  const RenderResult r = stress::renderText(R"({"render": {"width": 48, "height": 48, "spp": 4,
      "background": [1,1,1], "max_depth": 64},
    "camera": {"eye": [0,0,3.2], "look_at": [0,0,0], "vfov": 45},
    "materials": {"g": {"type": "dielectric", "ior": 1.5}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "g"}]})");
  double maxL = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) maxL = std::max(maxL, double(r.film.pixel(x, y)[0]));
  EXPECT_LE(maxL, 1 + 1e-4);
  EXPECT_GT(maxL, 0.9);
}

// 10. Nested media, glass (1.5) inside water (1.33) inside air: a ray at 35° through a stack of
// horizontal slabs is displaced sideways exactly as Snell's law says. The target is a stripe
// 2e-5 wide, lit only by ambient light: the pixel sees it only if the ray lands within 1e-5 of
// the prediction, and does not see stripes 3e-5 to either side.
TEST(NestedMedia, LateralShiftThroughGlassInWaterMatchesSnell) {
  const double theta = 35 * 3.14159265358979323846 / 180;
  const double sinT = std::sin(theta);
  const auto tanOf = [&](double n) {
    const double s = sinT / n;
    return s / std::sqrt(1 - s * s);
  };
  // Eye at y = 5 heading down at θ: 3 units of air, 1 of water, 2 of glass, 1 of water, 1 of air.
  const double x0 = 0;
  const double landing =
      x0 + 3 * std::tan(theta) + 2 * tanOf(1.33) + 2 * tanOf(1.5) + std::tan(theta);
  const auto pixelFor = [&](double stripeCentre) {
    return stress::renderText(
               R"({"render": {"width": 1, "height": 1, "spp": 1, "sampler": "regular",
        "ambient": [1,1,1], "max_depth": 16},
      "camera": {"eye": )" +
               vec(x0, 5, 0) + R"(, "look_at": )" + vec(x0 + 5 * std::tan(theta), 0, 0) +
               R"(, "vfov": 1},
      "materials": {"water": {"type": "dielectric", "ior": 1.33}, "glass": {"type": "dielectric", "ior": 1.5},
                    "lit": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
      "objects": [{"type": "box", "min": [-50,-2,-50], "max": [50,2,50], "material": "water"},
                  {"type": "box", "min": [-40,-1,-40], "max": [40,1,40], "material": "glass"},
                  {"type": "quad", "corner": )" +
               vec(stripeCentre - 1e-5, -3, -10) + R"(, "edge1": [2e-5,0,0],
                   "edge2": [0,0,20], "material": "lit"}]})")
        .film.pixel(0, 0)[0];
  };
  EXPECT_GT(pixelFor(landing), 0.5) << "the refracted ray missed x = " << landing;
  EXPECT_EQ(pixelFor(landing - 3e-5), 0.0);
  EXPECT_EQ(pixelFor(landing + 3e-5), 0.0);
}

// 12. Phong exponents 0 … 1e8, including cosines ≤ 0 (the back of the highlight). Guards:
// pow(0, 0), pow of negatives, overflow. Criterion: every pixel finite and ≤ k_d + k_s + k_a·I_a.
TEST(PhongExponents, ExtremeExponentsStayFiniteAndBounded) {
  for (double p : {0.0, 1e-3, 1e4, 1e6, 1e8}) {
    const RenderResult r = stress::renderText(
        R"({"render": {"width": 24, "height": 24, "spp": 1, "ambient": [0.1,0.1,0.1]},
      "camera": {"eye": [0,0,4], "look_at": [0,0,0]},
      "materials": {"m": {"type": "phong", "kd": [0.5,0.5,0.5], "ks": [0.5,0.5,0.5], "exponent": )" +
        num(p) +
        R"(, "specular_model": "phong"}},
      "lights": [{"type": "point", "position": [2,2,3]}, {"type": "directional", "direction": [0,0,1]}],
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
    EXPECT_EQ(r.stats.rays.nonfiniteSamples, 0u) << p;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x) {
        const double v = r.film.pixel(x, y)[0];
        ASSERT_TRUE(std::isfinite(v)) << p;
        ASSERT_LE(v, 2 * (0.5 + 0.5) + 0.05 + 1e-6) << "exponent " << p;  // two unit lights
      }
  }
}

// 13. Tiny and zero-area lights: a zero-area quad light is rejected at load with its location;
// one of area 1e-12 converges to the point light at its centre within 1e-3.
TEST(TinyLights, ZeroAreaRejectedTinyAreaIsAPointLight) {
  try {
    test::sceneFromText(R"({"camera": {"eye": [0,0,4], "look_at": [0,0,0]},
      "lights": [{"type": "quad", "corner": [0,2,0], "edge1": [1,0,0], "edge2": [2,0,0]}], "objects": []})");
    ADD_FAILURE() << "a zero-area light was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json:2: lights[0]"), std::string::npos) << e.what();
  }
  const auto withLight = [](const std::string& light) {
    return stress::renderText(R"({"render": {"width": 16, "height": 16, "spp": 2},
      "camera": {"eye": [0,2,4], "look_at": [0,0,0]},
      "materials": {"m": {"type": "phong", "kd": [0.8,0.8,0.8], "ks": [0.3,0.3,0.3]}},
      "lights": [)" + light + R"(],
      "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"},
                  {"type": "sphere", "center": [0,0.5,0], "radius": 0.5, "material": "m"}]})")
        .film;
  };
  const Film point = withLight(R"({"type": "point", "position": [1,3,1]})");
  const Film tiny =
      withLight(R"({"type": "quad", "corner": [0.9999995,3,0.9999995], "edge1": [1e-6,0,0],
      "edge2": [0,0,1e-6], "samples": 2})");
  // Its samples lie within 7.1e-7 of the point light's position, at least 2 units from every
  // lit point: directions turn by at most 3.5e-7 rad, which moves k_d·cosθ (0.8) by 2.8e-7 and
  // the highlight (k_s 0.3, exponent 32) by at most 0.3·32·1.8e-7 = 1.7e-6. No falloff.
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) ASSERT_NEAR(tiny.pixel(x, y)[0], point.pixel(x, y)[0], 1e-5);
}

// 14. Depth of field: aperture 0 is the pinhole bit for bit; a focus distance ≤ 0 is rejected.
TEST(DepthOfFieldLimits, ApertureZeroAndBadFocus) {
  const std::string body = R"(, "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "lights": [{"type": "point", "position": [1,2,3]}],
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})";
  const std::string head =
      R"({"render": {"width": 16, "height": 16, "spp": 4}, "camera": {"eye": [0,0,4])";
  EXPECT_EQ(stress::renderText(head + ", \"aperture_radius\": 0" + body).film.toFloatRgba(),
            stress::renderText(head + body).film.toFloatRgba());
  for (const char* bad : {"0", "-1"})
    EXPECT_THROW(
        test::sceneFromText(head + ", \"aperture_radius\": 0.1, \"focus_distance\": " + bad + body),
        SceneError);
}

// 15. Motion: identical keys render as the static scene; a rotation of 270° between two keys
// follows slerp's shorter arc, i.e. −90° (documented in docs/effects.md). A sphere at angle 0
// then sweeps through −45°, never through +135°.
TEST(MotionLimits, IdenticalKeysAndLargeRotations) {
  const std::string still = R"({"render": {"width": 16, "height": 16, "spp": 4},
    "camera": {"eye": [0,0,6], "look_at": [0,0,0], "shutter": [0,1]},
    "materials": {"m": {"type": "phong"}}, "lights": [{"type": "point", "position": [1,2,3]}],
    "objects": [{"type": "sphere", "center": [0.5,0,0], "radius": 0.5, "material": "m"}]})";
  std::string keyed = still;
  keyed.insert(keyed.rfind("}]"), R"(, "motion": {"center": [[0.5,0,0], [0.5,0,0]]})");
  EXPECT_EQ(stress::renderText(keyed).film.toFloatRgba(),
            stress::renderText(still).film.toFloatRgba());

  const Film f = stress::renderText(R"({"render": {"width": 64, "height": 64, "spp": 64,
                                                  "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 2.4, "shutter": [0,1]},
    "materials": {"m": {"type": "phong"}},
    "groups": {"ball": [{"type": "sphere", "center": [1,0,0], "radius": 0.15, "material": "m"}]},
    "objects": [{"type": "instance", "group": "ball",
                 "motion": {"transform": [{"rotate": [0,0,1,0]}, {"rotate": [0,0,1,270]}]}}]})")
                     .film;
  const auto pixelAt = [](double angleDeg) {
    const double a = angleDeg * 3.14159265358979323846 / 180;
    return std::pair{int((std::cos(a) + 1.2) / 2.4 * 64), int((1.2 - std::sin(a)) / 2.4 * 64)};
  };
  const auto [xs, ys] = pixelAt(-45);
  const auto [xl, yl] = pixelAt(135);
  EXPECT_GT(f.pixel(xs, ys)[3], 0.05);  // on the −90° arc
  EXPECT_EQ(f.pixel(xl, yl)[3], 0.0);   // the long way round is not taken
}

// 17. Facing mirrors: two parallel Phong mirrors (k_m = 0.9, ambient k_a·I_a = 0.1) with the
// camera between them at normal incidence. Guards: non-termination, energy growth. Criterion:
// the pixel is the partial geometric series 0.1·Σ_{k=0..D} 0.9^k for D = 0, 1, 64, within
// 1e-6 relative (at D = 64, 0.9^64 ≈ 1.2e-3 > 1/1024, so the throughput cutoff takes nothing).
TEST(FacingMirrors, GeometricSeriesAtEveryDepthLimit) {
  for (int depth : {0, 1, 64}) {
    const double v = stress::renderText(R"({"render": {"width": 1, "height": 1, "spp": 1,
        "sampler": "regular", "max_depth": )" +
                                        std::to_string(depth) + R"(, "ambient": [0.1,0.1,0.1]},
      "camera": {"type": "orthographic", "eye": [0,0,0], "look_at": [0,0,-1], "height": 0.01},
      "materials": {"m": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0], "km": [0.9,0.9,0.9]}},
      "objects": [{"type": "quad", "corner": [-1,-1,-1], "edge1": [2,0,0], "edge2": [0,2,0], "material": "m"},
                  {"type": "quad", "corner": [-1,-1,1], "edge1": [2,0,0], "edge2": [0,2,0], "material": "m"}]})")
                         .film.pixel(0, 0)[0];
    const double expected = 0.1 * (1 - std::pow(0.9, depth + 1)) / (1 - 0.9);
    EXPECT_NEAR(v, expected, 1e-6 * expected) << "max_depth " << depth;
  }
}

// 17b. Glass that gains light: two nested glass spheres with a surface mirror k_m = 1, so each
// hit sends on twice what reaches it (k_m + R + (1 − R) = 2) and no path's product of weights
// falls: the ray tree grew about 1.8 times with each depth, and max_depth 1000 never finished.
// Guards: exponential work from a small scene. Criterion: a branch's share halves at each hit
// (branchShare), so none past depth 10 reaches the cutoff 2⁻¹⁰: the render at max_depth 1000
// is the one at max_depth 10, bit for bit, and a sample traces at most its camera ray and,
// at each depth k ≤ 10, min(3^k, 1024) rays (three a hit; a depth's shares add to at most 1).
TEST(GainingGlass, RaysStopAtTheCutoffWhateverTheDepthLimit) {
  const auto scene = [](int depth) {
    return R"({"render": {"width": 8, "height": 8, "spp": 1, "max_depth": )" +
           std::to_string(depth) + R"(, "background": [0.5,0.5,0.5]},
      "camera": {"eye": [0,0,5], "look_at": [0,0,0], "vfov": 30},
      "materials": {"glass": {"type": "dielectric", "ior": 1.5, "km": [1,1,1]}},
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"},
                  {"type": "sphere", "center": [0,0,0], "radius": 0.5, "material": "glass"}]})";
  };
  const RenderResult deep = stress::renderText(scene(1000));
  const RenderResult ten = stress::renderText(scene(10));
  EXPECT_EQ(deep.stats.rays.total(), ten.stats.rays.total());
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(deep.film.pixel(x, y)[c], ten.film.pixel(x, y)[c]);
  uint64_t perSample = 1;
  for (uint64_t k = 1, width = 3; k <= 10; ++k, width *= 3)
    perSample += std::min<uint64_t>(width, 1024);
  EXPECT_LE(deep.stats.rays.total(), 64 * perSample);
  // The glass splits: far more than one ray a sample crosses it.
  EXPECT_GT(deep.stats.rays.refraction, 64u * 4);
}

// 18. A NaN produced at runtime (forced through the render's sample hook) is counted, logged,
// and never written: the pixel keeps the mean of its finite samples.
TEST(RuntimeNaN, CountedLoggedAndNeverWritten) {
  testing::internal::CaptureStderr();
  const RenderResult r = stress::renderText(
      R"({"render": {"width": 4, "height": 4, "spp": 4, "background": [0.5,0.5,0.5]},
        "camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "objects": []})",
      AccelKind::Embree, [](int x, int y, Radiance& s) {
        if (x == 1 && y == 2) s.L.g = std::nanf("");
      });
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.stats.rays.nonfiniteSamples, 4u);  // every sample of pixel (1, 2)
  EXPECT_NE(log.find("non-finite sample at pixel (1, 2)"), std::string::npos) << log;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(r.film.pixel(x, y)[c]));
  EXPECT_EQ(r.film.pixel(1, 2)[0], 0.0);  // no finite sample left: black
  EXPECT_EQ(r.film.pixel(0, 0)[0], 0.5);
}

// 19. I/O faults: an unwritable directory (a read-only filesystem) is found before rendering, an
// output that cannot be used as given (exit 2); a full disk (a 1-block file size limit) only
// while writing (exit 1). Both leave the previous file intact.
TEST(IoFaults, UnwritableDirectoryAndFullDisk) {
  const auto r =
      test::runGlint("render --quiet --width 8 --height 8 --spp 1 -o /proc/glint-test.exr");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("cannot write /proc/glint-test.exr"), std::string::npos) << r.output;
  const std::string target = (test::tempDir() / "keep.exr").string();
  std::ofstream(target) << "old frame";
  const std::string cmd = "bash -c 'ulimit -f 1; exec " + std::string(GLINT_BINARY) +
                          " render --quiet --width 300 --height 200 --spp 1 -o " + target +
                          "' > /dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
  std::ifstream f(target);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(f), {}), "old frame");
}

// 19b. A really full disk: a 64 KiB tmpfs holding the previous frame, and a render whose EXR
// needs ~1 MB. Guards: ENOSPC met mid-write (not only at open) leaving a truncated file or a
// stray temporary. Criterion: exit 1, the error names the path, the old file is intact and
// nothing else is left on the filesystem. Needs root to mount (CI runs as root).
TEST(IoFaults, FullFilesystemKeepsThePreviousFile) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a tmpfs needs root";
  const std::filesystem::path dir = test::tempDir() / "tinyfs";
  std::filesystem::create_directories(dir);
  const std::string mount = "mount -t tmpfs -o size=64k tmpfs " + dir.string() + " 2>/dev/null";
  if (std::system(mount.c_str()) != 0) GTEST_SKIP() << "cannot mount a tmpfs here";
  const std::string target = (dir / "frame.exr").string();
  std::ofstream(target) << "old frame";
  const auto r = test::runGlint(
      "render --quiet --width 300 --height 200 --spp 1 --compression none -o " + target);
  std::ifstream f(target);
  const std::string kept(std::istreambuf_iterator<char>(f), {});
  f.close();
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  std::system(("umount " + dir.string()).c_str());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(target), std::string::npos) << r.output;
  EXPECT_EQ(kept, "old frame");
  EXPECT_EQ(entries, 1u) << "a temporary file was left behind";
}

}  // namespace
}  // namespace glint
