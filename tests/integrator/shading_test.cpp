// The shading layer against closed forms (seed 000 §4.5–4.8, §13.1; seed 001 §5–7).
#include <gtest/gtest.h>

#include "integrator/optics.h"
#include "integrator/whitted.h"
#include "test_util.h"

namespace glint {
namespace {

struct Traced {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
  Rgb trace(const Ray& ray, float minThroughput = kDefaultMinThroughput) const {
    RayCounters counters;
    const Sampler sampler(SamplerKind::Stratified, 1, 0);
    return WhittedIntegrator(scene, *accel, minThroughput)
        .trace(ray, SampleKey{&sampler, 0, 0, 0}, counters)
        .L;
  }
};

// The eye sits at the world origin, so render space (world − eye, io/placement.h) is world
// space and the rays below are written in world coordinates.
Traced load(const std::string& body) {
  Traced t{
      test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]}, )" + body + "}"),
      nullptr};
  t.accel = makeAccelerator(AccelKind::Embree, t.scene);
  return t;
}

Ray rayTo(Vec3f from, Vec3f to) { return {from, normalize(to - from)}; }

// spawnRay moves an origin off the surface by its error bound: for a face at coordinate c
// (all vertices at c) that is γ₇·|c| ≈ 3.5 ulps of c, plus one ulp of rounding. A path through
// an absorbing medium is shortened by that at each entry, and Beer's factor a^s errs by about
// |ln a|·(shortening) relative. Tolerances use 16 ulps of c, above that bound.
double spawnOffset(float coordinate) {
  return 16.0 * (std::nextafter(coordinate, kInfinity) - coordinate);
}

TEST(Shading, LambertUnderPointLightWithFalloff) {
  // Light at (1, 2, 0) over the origin: cosθ = 2/√5, r² = 5 → L = k_d·I·cosθ / r².
  const auto t = load(R"("materials": {"m": {"type": "phong", "kd": [0.6,0.6,0.6], "ka": [0,0,0]}},
    "lights": [{"type": "point", "position": [1,2,0], "intensity": [3,3,3], "falloff": "inverse_square"}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])");
  const Rgb L = t.trace(rayTo({0, 1, 3}, {0, 0, 0}));
  EXPECT_NEAR(L.r, 0.6f * 3 * (2 / std::sqrt(5.0f)) / 5, 1e-6);
}

std::string specularScene(const char* model) {
  return std::string(R"("materials": {"m": {"type": "phong", "kd": [0.2,0.2,0.2], "ka": [0,0,0],
      "ks": [0.5,0.5,0.5], "exponent": 10, "specular_model": ")") +
         model + R"("}},
    "lights": [{"type": "point", "position": [-1,1,0], "intensity": [1,1,1]}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])";
}

TEST(Shading, BlinnPhongPeakAndAngle) {
  // Light at 45° on one side, viewer at 45° on the other: h = n, so L = k_d cos45° + k_s.
  const auto t = load(specularScene("blinn"));
  EXPECT_NEAR(t.trace(rayTo({1, 1, 0}, {0, 0, 0})).r, 0.2f * std::sqrt(0.5f) + 0.5f, 1e-6);
  // Viewer at 60° from the normal: h sits at (60° − 45°)/2 = 7.5° → k_s·cos(7.5°)^10.
  const float a = 60 * kPi / 180;
  const Rgb L = t.trace(rayTo({std::sin(a), std::cos(a), 0}, {0, 0, 0}));
  EXPECT_NEAR(L.r, 0.2f * std::sqrt(0.5f) + 0.5f * std::pow(std::cos(7.5f * kPi / 180), 10.0f),
              1e-6);
}

TEST(Shading, PhongPeakAndAngle) {
  // Phong uses r·v: r is the mirror of the light direction (45°), so 15° off at a 60° viewer.
  const auto t = load(specularScene("phong"));
  EXPECT_NEAR(t.trace(rayTo({1, 1, 0}, {0, 0, 0})).r, 0.2f * std::sqrt(0.5f) + 0.5f, 1e-6);
  const float a = 60 * kPi / 180;
  const Rgb L = t.trace(rayTo({std::sin(a), std::cos(a), 0}, {0, 0, 0}));
  EXPECT_NEAR(L.r, 0.2f * std::sqrt(0.5f) + 0.5f * std::pow(std::cos(15 * kPi / 180), 10.0f), 1e-6);
}

TEST(Shading, CheckerTexture) {
  // Scale 1: the cell of (0.5, 0, 0.5) is even → a; (1.5, 0, 0.5) is odd → b. Ambient only.
  const auto t = load(R"("render": {"ambient": [1,1,1]},
    "materials": {"m": {"type": "phong", "kd": {"checker": {"scale": 1, "a": [0.9,0.9,0.9], "b": [0.1,0.1,0.1]}}}},
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])");
  EXPECT_NEAR(t.trace(rayTo({0.5f, 1, 0.5f}, {0.5f, 0, 0.5f})).r, 0.9f, 1e-7);
  EXPECT_NEAR(t.trace(rayTo({1.5f, 1, 0.5f}, {1.5f, 0, 0.5f})).r, 0.1f, 1e-7);
}

TEST(Shading, MirrorFacingUniformBackground) {
  // Every reflected ray escapes to the background: L = k_m × background, exactly.
  const auto t = load(R"("render": {"background": [0.5, 0.25, 1]},
    "materials": {"m": {"type": "mirror", "km": [0.9, 0.8, 0.7]}},
    "objects": [{"type": "quad", "corner": [-1,-1,0], "edge1": [2,0,0], "edge2": [0,2,0], "material": "m"}])");
  const Rgb L = t.trace(rayTo({0.3f, 0.2f, 5}, {0, 0, 0}));
  EXPECT_EQ(L.r, 0.9f * 0.5f);
  EXPECT_EQ(L.g, 0.8f * 0.25f);
  EXPECT_EQ(L.b, 0.7f * 1.0f);
}

// A glass slab of thickness 0.5 (z in [−0.25, 0.25]) seen at normal incidence against a
// background of 1; a black wall behind the viewer absorbs everything reflected back.
std::string slabScene(const char* attenuation, int maxDepth) {
  return std::string(R"("render": {"background": [1,1,1], "max_depth": )") +
         std::to_string(maxDepth) + R"(},
    "materials": {"g": {"type": "dielectric", "ior": 1.5, "attenuation": )" +
         attenuation +
         R"(}, "black": {"type": "phong", "kd": [0,0,0], "ka": [0,0,0]}},
    "objects": [{"type": "box", "min": [-50,-50,-0.25], "max": [50,50,0.25], "material": "g"},
                {"type": "quad", "corner": [-50,-50,8], "edge1": [100,0,0], "edge2": [0,100,0], "material": "black"}])";
}

// Transmission of the slab summed over internal bounces k = 0..K:
// (1 − R)²·A·Σ (R²A²)^k with A = a^d the Beer factor of one crossing.
double slabSeries(double R, double A, int K) {
  double sum = 0;
  for (int k = 0; k <= K; ++k) sum += std::pow(R * R * A * A, k);
  return (1 - R) * (1 - R) * A * sum;
}

TEST(Shading, GlassSlabAtNormalIncidence) {
  const double R = 0.04;  // ((1.5 − 1)/(1.5 + 1))²
  // Camera ray at depth 0; the k-th internal bounce leaves at depth 2 + 2k ≤ max_depth = 8,
  // so k = 0..3 are traced when no throughput cutoff applies.
  const auto clear = load(slabScene("[1,1,1]", 8));
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  EXPECT_NEAR(clear.trace(ray, 0).r, slabSeries(R, 1, 3), 1e-6);
  // With Beer: a = (0.5, 0.8, 1) per unit over d = 0.5 → A = a^0.5 per crossing.
  const auto tinted = load(slabScene("[0.5,0.8,1]", 8));
  const Rgb L = tinted.trace(ray, 0);
  // Each crossing starts a few ulps of 0.25 inside the slab; the direct path dominates the sum.
  const double beerTol = std::fabs(std::log(0.5)) * spawnOffset(0.25f) * 1.1;
  EXPECT_NEAR(L.r, slabSeries(R, std::sqrt(0.5), 3), beerTol);
  EXPECT_NEAR(L.g, slabSeries(R, std::sqrt(0.8), 3), beerTol);
  EXPECT_NEAR(L.b, slabSeries(R, 1, 3), 1e-6);
  // max_depth 2 keeps only the direct crossing (k = 0).
  EXPECT_NEAR(load(slabScene("[1,1,1]", 2)).trace(ray, 0).r, slabSeries(R, 1, 0), 1e-6);
}

TEST(Shading, ThroughputCutoffChangesNoPixelByMoreThanItsBound) {
  // The cutoff drops branches whose weight is below 1/1024; behind them is radiance ≤ 1 here,
  // so the pixel moves by less than 1/1024 — on the slab it drops the k ≥ 2 bounces (weight
  // (1−R)²R⁴ ≈ 2.4e-6) and keeps k = 1 ((1−R)²R² ≈ 1.5e-3).
  const auto clear = load(slabScene("[1,1,1]", 8));
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  const float exact = clear.trace(ray, 0).r;
  const float cut = clear.trace(ray).r;
  EXPECT_LE(std::fabs(exact - cut), kDefaultMinThroughput);
  EXPECT_NEAR(cut, slabSeries(0.04, 1, 1), 1e-6);
}

TEST(Shading, NestedDielectricsUseTheSurroundingMedium) {
  // A glass sphere (1.5) inside a water sphere (1.33), both centred: at normal incidence the
  // glass interface reflects ((1.5 − 1.33)/(1.5 + 1.33))², not ((1.5 − 1)/(1.5 + 1))². With a
  // black wall behind the viewer and background 1 beyond, the transmitted light is
  // (1−R_w)²(1−R_g)² with one pass (no bounces traced at max_depth 4).
  const auto t = load(R"("render": {"background": [1,1,1], "max_depth": 4},
    "materials": {"glass": {"type": "dielectric", "ior": 1.5},
                  "water": {"type": "dielectric", "ior": 1.33},
                  "black": {"type": "phong", "kd": [0,0,0], "ka": [0,0,0]}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 2, "material": "water"},
                {"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"},
                {"type": "quad", "corner": [-50,-50,8], "edge1": [100,0,0], "edge2": [0,100,0], "material": "black"}])");
  const double Rw = std::pow(0.33 / 2.33, 2), Rg = std::pow(0.17 / 2.83, 2);
  EXPECT_NEAR(t.trace({{0, 0, 5}, {0, 0, -1}}, 0).r, (1 - Rw) * (1 - Rw) * (1 - Rg) * (1 - Rg),
              1e-6);
}

TEST(Shading, TransparentShadowsCarryFresnelAndBeer) {
  // A light above a glass slab (thickness 1, a = 0.5) over a Lambert floor. The vertical shadow
  // ray crosses two interfaces at normal incidence and one unit of glass: T = (1 − 0.04)²·0.5.
  const std::string body = R"(,
    "materials": {"g": {"type": "dielectric", "ior": 1.5, "attenuation": [0.5,0.5,0.5]},
                  "m": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}},
    "lights": [{"type": "point", "position": [0,5,0], "intensity": [1,1,1]}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"},
                {"type": "box", "min": [-1,1,-1], "max": [1,2,1], "material": "g"}])";
  const Ray ray = rayTo({3, 0.5f, 0}, {0, 0, 0});  // sees the floor below the slab, from the side
  const auto opaque = load(R"("render": {"transparent_shadows": false})" + body);
  EXPECT_EQ(opaque.trace(ray).r, 0.0f);
  const auto clear = load(R"("render": {"transparent_shadows": true})" + body);
  // The shadow ray re-enters the glass a few ulps above y = 1 (see spawnOffset).
  EXPECT_NEAR(clear.trace(ray).r, 0.96 * 0.96 * 0.5,
              0.96 * 0.96 * 0.5 * std::log(2.0) * spawnOffset(1.0f) * 1.1);
}

TEST(Shading, GlassSphereConservesEnergy) {
  // No lights, no absorption, background 1: every path ends in the background with total
  // weight ≤ 1, so no pixel may exceed 1 (+1e-4 for float rounding).
  Scene s = test::sceneFromText(
      R"({"render": {"width": 32, "height": 32, "spp": 4, "background": [1,1,1], "max_depth": 16},
    "camera": {"eye": [0,0,4], "look_at": [0,0,0], "vfov": 35},
    "materials": {"g": {"type": "dielectric", "ior": 1.5}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "g"}]})");
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  const WhittedIntegrator integrator(s, *accel, 0);
  RayCounters counters;
  const Sampler sampler(SamplerKind::Stratified, 1, 0);
  float maxL = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      Ray r = rayTo({0, 0, 4}, {-1.2f + 2.4f * float(x) / 63, -1.2f + 2.4f * float(y) / 63, 0});
      const Rgb L = integrator.trace(r, SampleKey{&sampler, x, y, 0}, counters).L;
      maxL = std::max(maxL, L.maxChannel());
    }
  EXPECT_LE(maxL, 1.0f + 1e-4f);
  EXPECT_GT(maxL, 0.5f);  // the sphere transmits most of the background: not trivially dark
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(Shading, CheckerStaysFixedInTheWorldWhereverTheCameraIs) {
  // Scenes load into render space (world − eye); the checker must still count world cells.
  // Straight down from each eye the ray meets the plane y = 0 at world (x, 0, z); ambient light
  // only, so the pixel is the checker colour there. Eyes one cell apart flip the colour; eyes
  // two cells apart (and 1e5 away, an even number of cells) do not.
  struct Case {
    double x, y, z;
    float expected;  // 0.9 = cell sum even (a), 0.1 = odd (b)
  };
  for (const Case c : {Case{0.5, 5, 0.5, 0.9f}, Case{0.5, 6, 0.5, 0.9f}, Case{1.5, 5, 0.5, 0.1f},
                       Case{2.5, 7, -0.5, 0.1f}, Case{100000.5, 5, 0.5, 0.9f}}) {
    const auto at = [&](double y) {
      return "[" + std::to_string(c.x) + ", " + std::to_string(y) + ", " + std::to_string(c.z) +
             "]";
    };
    Traced t{test::sceneFromText(R"({"render": {"ambient": [1,1,1]},
      "camera": {"eye": )" + at(c.y) +
                                 R"(, "look_at": )" + at(0) + R"(, "up": [0,0,-1]},
      "materials": {"m": {"type": "phong", "kd": [0,0,0],
        "ka": {"checker": {"scale": 1, "a": [0.9,0.9,0.9], "b": [0.1,0.1,0.1]}}}},
      "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}]})"),
             nullptr};
    t.accel = makeAccelerator(AccelKind::Embree, t.scene);
    const Rgb L = t.trace({{0, 0, 0}, {0, -1, 0}});  // from the eye, in render space
    EXPECT_FLOAT_EQ(L.r, c.expected) << "eye " << at(c.y);
  }
}

}  // namespace
}  // namespace glint
