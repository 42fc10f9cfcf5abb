// Self-intersection ("black dots", seed 001 §9 item 5) and leaks across scales: spawnRay's
// scale-aware offset must neither re-hit the source surface nor jump through a thin gap.
#include <gtest/gtest.h>

#include "materials/fresnel.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// A number as a test-name fragment: gtest names allow only letters, digits and '_'.
std::string label(double v) {
  std::string s = num(v);
  for (char& c : s)
    if (c == '.')
      c = 'p';
    else if (c == '-')
      c = 'm';
    else if (c == '+')
      c = 'P';
  return s;
}

std::string vec(double x, double y, double z) {
  return "[" + num(x) + "," + num(y) + "," + num(z) + "]";
}

Film render(const std::string& text) {
  const Scene s = test::sceneFromText(text);
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(s, *accel, opt).film;
}

TEST(SampleSets, SetsBeyondTheSamplersLimitAreRefusedBeforeRendering) {
  // kMaxSampleSet = 2^28 samples in one pixel's set (render_job.h): spp alone, or spp × an area
  // light's samples. At the limit a scene passes; one past it, it is refused with a message
  // that names the numbers and the light.
  Scene s = test::sceneFromText(R"({
    "render": {"width": 2, "height": 2, "spp": 1048576},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [0, 5, 0]},
               {"type": "quad", "corner": [0, 5, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                "samples": 256}],
    "objects": []})");
  EXPECT_NO_THROW(checkSampleSets(s, s.render.spp));  // 2^20 × 2^8 = 2^28
  s.render.spp = 1048577;
  try {
    checkSampleSets(s, s.render.spp);
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("spp 1048577 × the 256 samples of lights[1]"),
              std::string::npos)
        << e.what();
  }
  // renderScene refuses it before drawing a sample.
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  RenderOptions opt;
  opt.progress = false;
  EXPECT_THROW(renderScene(s, *accel, opt), UsageError);
  // spp alone: 2^28 passes (with no area light), 2^28 + 1 does not.
  s.lights.resize(1);
  s.render.spp = 1 << 28;
  EXPECT_NO_THROW(checkSampleSets(s, s.render.spp));
  s.render.spp = (1 << 28) + 1;
  EXPECT_THROW(checkSampleSets(s, s.render.spp), UsageError);
}

TEST(FrameMemory, AFrameThatCannotFitIsRefusedWithItsSize) {
  // pixels × bytes a pixel: 1000 pixels of 64 bytes need 64 000 bytes.
  EXPECT_NO_THROW(checkFrameFits(1000, 64, 64000));
  EXPECT_NO_THROW(checkFrameFits(1000, 64, 0));  // unknown memory: no check
  try {
    checkFrameFits(1000, 64, 63999);
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("a frame of 1000 pixels needs about"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("64 bytes a pixel"), std::string::npos) << e.what();
  }
  // A 32768² frame with depth, normal and albedo AOVs (7 channels of 20 bytes) beside its
  // colour and sampling state (137): 277 bytes a pixel, 3.0e11 bytes in all, more than 100 GiB;
  // the message names the parts it is given.
  try {
    checkFrameFits(int64_t{1} << 30, 277, uint64_t{100} << 30,
                   "colour and sampling state 137 and AOVs 140");
    FAIL() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "(277 bytes a pixel: colour and sampling state 137 and AOVs 140)"),
              std::string::npos)
        << e.what();
  }
}

struct Placement {
  double scale, offset;
};

class LitSurfaces : public ::testing::TestWithParam<Placement> {};

TEST_P(LitSurfaces, NoLitPointIsReportedInShadow) {
  // A quad and a box top (two triangles) of size `scale` at height 0, `offset` from the origin,
  // lit by a directional light 60° from the normal: every pixel must read k_d·cos60° = 0.4
  // within 1e-4 relative. A re-hit of the source surface would read 0.
  const double s = GetParam().scale, o = GetParam().offset;
  const Film film =
      render(R"({"render": {"width": 24, "height": 12, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": )" +
             vec(o, 3 * s, o) + R"(, "look_at": )" + vec(o, 0, o) +
             R"(, "up": [0,0,-1], "height": )" + num(0.9 * s) + R"(},
    "materials": {"m": {"type": "phong", "kd": [0.8,0.8,0.8], "ka": [0,0,0]}},
    "lights": [{"type": "directional", "direction": [0.8660254, -0.5, 0], "intensity": [1,1,1]}],
    "objects": [
      {"type": "quad", "corner": )" +
             vec(o - s, 0, o - 0.5 * s) + R"(, "edge1": )" + vec(s, 0, 0) + R"(, "edge2": )" +
             vec(0, 0, s) + R"(, "material": "m"},
      {"type": "box", "min": )" +
             vec(o, -s, o - 0.5 * s) + R"(, "max": )" + vec(o + s, 0, o + 0.5 * s) +
             R"(, "material": "m"}]})");
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 24; ++x) {
      const float* p = film.pixel(x, y);
      ASSERT_EQ(p[3], 1.0) << "pixel misses the surfaces: the test setup is wrong";
      EXPECT_NEAR(p[0], 0.4, 0.4e-4) << "pixel " << x << "," << y;
    }
}

INSTANTIATE_TEST_SUITE_P(Scales, LitSurfaces,
                         ::testing::Values(Placement{1e-4, 0}, Placement{1, 0}, Placement{1e4, 0},
                                           Placement{1, 1e5}),
                         [](const auto& p) {
                           return "scale_" + label(p.param.scale) + "_offset_" +
                                  label(p.param.offset);
                         });

class ThinShell : public ::testing::TestWithParam<double> {};

TEST_P(ThinShell, GlassAroundAnOpaqueSphereLeaksNoLight) {
  // A black sphere of radius r inside a glass shell of radius r + 4e-5·r, background 1. The
  // refracted ray must stop on the black sphere, so a pixel at distance ρ from the centre reads
  // only the shell's reflection, F(cosθ) with cosθ = √(1 − (ρ/R)²). A leak would add ~0.9.
  const double r = GetParam(), R = r * (1 + 4e-5);
  constexpr int kN = 32;
  const Film film = render(R"({"render": {"width": 32, "height": 32, "spp": 1, "sampler": "regular",
      "background": [1,1,1], "max_depth": 8},
    "camera": {"type": "orthographic", "eye": )" +
                           vec(0, 0, 10 * r) + R"(, "look_at": [0,0,0],
      "height": )" + num(2 * R) +
                           R"(},
    "materials": {"glass": {"type": "dielectric", "ior": 1.5},
                  "black": {"type": "phong", "kd": [0,0,0], "ka": [0,0,0]}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": )" +
                           num(R) + R"(, "material": "glass"},
                {"type": "sphere", "center": [0,0,0], "radius": )" +
                           num(r) + R"(, "material": "black"}]})");
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const double u = (x + 0.5) / kN * 2 - 1, v = (y + 0.5) / kN * 2 - 1;  // in units of R
      const double rho2 = u * u + v * v;
      if (rho2 > 0.81) continue;  // near the rim the refracted ray may genuinely skim the gap
      const float expected = fresnelDielectric(float(std::sqrt(1 - rho2)), 1, 1.5f);
      EXPECT_NEAR(film.pixel(x, y)[0], expected, 1e-4) << "pixel " << x << "," << y;
    }
}

INSTANTIATE_TEST_SUITE_P(Scales, ThinShell, ::testing::Values(1e-3, 1.0, 1e3),
                         [](const auto& p) { return "radius_" + label(p.param); });

}  // namespace
}  // namespace glint
