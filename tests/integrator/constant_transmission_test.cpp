// Seed 002's coherent transmission coefficient k_t (§9.1, eq. 9.22; "fresnel": "none"): the
// interface transmits k_t, constant, and a shadow ray through transparent objects carries the
// product of the k_t of every interface it crosses, refraction ignored.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// A white Lambert floor (k_d 1, no ambient) under a directional light travelling along
// (1, −1, 0)/√2, seen straight down by an orthographic camera over x ∈ [−1.5, 1.5]: 60 columns
// of 0.05. Slab A (x ∈ [−0.5, 0.5], y ∈ [1, 1.2]) and slab B (x ∈ [−0.8, 0], y ∈ [1.4, 1.6])
// both lie on the way to the light of the floor at x ∈ [1.1, 1.15] (column 52): its shadow ray
// climbs at 45° and crosses A between x = 0.1 and −0.1, B between −0.3 and −0.5, entering and
// leaving each through its bottom and top. The floor at x ∈ [−1, −0.95] (column 10) sees the
// light past both. `slabs` are the extra objects.
std::string floorScene(const std::string& glass, const std::string& slabs) {
  return R"({"render": {"width": 60, "height": 2, "spp": 1, "transparent_shadows": true},
    "camera": {"type": "orthographic", "eye": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
               "window": [-1.5, 1.5, -0.05, 0.05]},
    "materials": {"floor": {"type": "phong", "kd": [1, 1, 1], "ka": [0, 0, 0]},
                  "glass": )" +
         glass + R"(},
    "lights": [{"type": "directional", "direction": [1, -1, 0], "intensity": [1, 1, 1]}],
    "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"})" +
         slabs + "]}";
}

const char* kSlabA = R"(, {"type": "box", "min": [-0.5, 1, -1], "max": [0.5, 1.2, 1],
                           "material": "glass"})";
const char* kSlabB = R"(, {"type": "box", "min": [-0.8, 1.4, -1], "max": [0, 1.6, 1],
                           "material": "glass"})";
const char* kGlass = R"({"type": "dielectric", "ior": 1.5, "fresnel": "none",
                         "kt": [0.5, 0.6, 0.8]})";

Film render(const std::string& text) {
  const Scene scene = test::sceneFromText(text);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(scene, *accel, opt).film;
}

// Floating-point rounding only: a cosine and a product of a handful of factors.
constexpr double kRounding = 1e-6;

TEST(ConstantTransmission, ASlabsShadowReadsKtSquaredOfTheLitFloor) {
  const Film f = render(floorScene(kGlass, kSlabA));
  const double lit = std::sqrt(0.5);  // k_d · cos 45°
  const double kt[3] = {0.5, 0.6, 0.8};
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f.pixel(10, 0)[c], lit, kRounding) << c;
    // Two interfaces, k_t at each: k_t² per channel.
    EXPECT_NEAR(f.pixel(52, 0)[c], kt[c] * kt[c] * lit, kRounding) << c;
    // The camera looks down through the slab at x ∈ [0, 0.05] (column 30), at normal
    // incidence: its refracted ray carries k_t at each interface, and the floor there is lit.
    EXPECT_NEAR(f.pixel(30, 0)[c], kt[c] * kt[c] * lit, kRounding) << c;
  }
}

TEST(ConstantTransmission, TwoSlabsShadowReadsKtToTheFourth) {
  const Film f = render(floorScene(kGlass, std::string(kSlabA) + kSlabB));
  const double lit = std::sqrt(0.5);
  const double kt[3] = {0.5, 0.6, 0.8};
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f.pixel(10, 0)[c], lit, kRounding) << c;
    EXPECT_NEAR(f.pixel(52, 0)[c], std::pow(kt[c], 4) * lit, kRounding) << c;
  }
}

TEST(ConstantTransmission, BeersLawStillAppliesInside) {
  // Attenuation 0.5 per unit: the shadow ray runs 0.2·√2 inside the slab at 45°, so k_t² ·
  // 0.5^(0.2·√2). spawnRay's offsets shorten the path inside by a few ulps of its ends.
  const Film f = render(floorScene(R"({"type": "dielectric", "ior": 1.5, "fresnel": "none",
      "kt": [0.5, 0.6, 0.8], "attenuation": [0.5, 0.5, 0.5]})",
                                   kSlabA));
  const double kt[3] = {0.5, 0.6, 0.8};
  const double beer = std::pow(0.5, 0.2 * std::sqrt(2.0));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(f.pixel(52, 0)[c], kt[c] * kt[c] * beer * std::sqrt(0.5), 1e-5) << c;
}

TEST(ConstantTransmission, FresnelGlassStaysTheDefault) {
  // Without "fresnel": "none" the interface transmits Fresnel's 1 − R. The unrefracted shadow
  // ray enters the slab at 45° and meets its top face from inside at 45° too, past glass's
  // critical angle (sin θ_t = 1.5·sin 45° > 1): total internal reflection, R = 1, so no light
  // reaches the floor where a k_t slab let k_t² through.
  const Film f = render(floorScene(R"({"type": "dielectric", "ior": 1.5})", kSlabA));
  for (int c = 0; c < 3; ++c) EXPECT_EQ(f.pixel(52, 0)[c], 0.0) << c;
  EXPECT_NEAR(f.pixel(10, 0)[0], std::sqrt(0.5), kRounding);
}

}  // namespace
}  // namespace glint
