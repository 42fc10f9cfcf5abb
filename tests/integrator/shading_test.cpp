// The shading layer against closed forms (seed 000 §4.5–4.8, §13.1; seed 001 §5–7).
#include <gtest/gtest.h>

#include "trace_both.h"

namespace glint {
namespace {

using test::load;
using test::rayTo;
using test::spawnOffset;

TEST(Shading, LambertUnderPointLightWithFalloff) {
  // Light at (1, 2, 0) over the origin: cosθ = 2/√5, r² = 5 → L = k_d·I·cosθ / r².
  const auto t = load(R"("materials": {"m": {"type": "phong", "kd": [0.6,0.6,0.6], "ka": [0,0,0]}},
    "lights": [{"type": "point", "position": [1,2,0], "intensity": [3,3,3], "falloff": "inverse_square"}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])");
  const Rgb L = t.trace(rayTo({0, 1, 3}, {0, 0, 0}));
  EXPECT_NEAR(L.r, 0.6f * 3 * (2 / std::sqrt(5.0f)) / 5, 1e-6);
}

TEST(Shading, SpotLightOnAFloorInsideAndOutsideItsCones) {
  // A spot 1 above the origin pointing down, inner 20°, outer 40°, no falloff; k_d 1 floor.
  // Under it: k_d·I·cos 0 = 1. At x = tan 30° the point is 30° off the axis: glTF's fade
  // t² = 0.331507 (lights/light.h, tested there) times cos 30° at the floor = 0.287094. Past
  // tan 40° = 0.8391: dark.
  const auto t = load(R"("materials": {"m": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}},
    "lights": [{"type": "spot", "position": [0,1,0], "direction": [0,-1,0], "intensity": [1,1,1],
                "inner_angle": 20, "outer_angle": 40}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])");
  EXPECT_NEAR(t.trace(rayTo({0, 0.5f, 2}, {0, 0, 0})).r, 1.0, 1e-6);
  const float x30 = std::tan(30 * kPi / 180);
  EXPECT_NEAR(t.trace(rayTo({x30, 0.5f, 2}, {x30, 0, 0})).r, 0.331507 * std::cos(30 * kPi / 180),
              1e-5);
  EXPECT_EQ(t.trace(rayTo({0.85f, 0.5f, 2}, {0.85f, 0, 0})).r, 0);
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
std::string slabScene(const char* attenuation, int maxDepth, const std::string& extra = "") {
  return std::string(R"("render": {"background": [1,1,1], "max_depth": )") +
         std::to_string(maxDepth) + R"(},
    "materials": {"g": {"type": "dielectric", "ior": 1.5, "attenuation": )" +
         attenuation + extra + R"(}, "black": {"type": "phong", "kd": [0,0,0]}},
    "objects": [{"type": "box", "min": [-50,-50,-0.25], "max": [50,50,0.25], "material": "g"},
                {"type": "quad", "corner": [-50,-50,8], "edge1": [100,0,0], "edge2": [0,100,0], "material": "black"}])";
}

// The slab's light at depth limit D (D ≥ 1), A the Beer factor of one crossing. The camera ray
// (depth 0) enters the front face; the ray of depth d ≥ 1 crosses the slab and meets the back
// face for odd d, the front face for even d, carrying (1 − R)·R^(d−1)·A^d. At a back face its
// refracted part (1 − R) leaves into the background (1) when d + 1 ≤ D. Past the limit Trace
// returns the background, so the deepest ray, of depth D, brings its whole weight back:
//   L = Σ_{k=0}^{⌊D/2⌋−1} (1 − R)²·R^{2k}·A^{2k+1} + (1 − R)·R^{D−1}·A^D.
double slabAtDepthLimit(double R, double A, int D) {
  double sum = 0;
  for (int k = 0; k < D / 2; ++k)
    sum += (1 - R) * (1 - R) * std::pow(R, 2 * k) * std::pow(A, 2 * k + 1);
  return sum + (1 - R) * std::pow(R, D - 1) * std::pow(A, D);
}

TEST(Shading, GlassSlabAtNormalIncidence) {
  const double R = 0.04;  // ((1.5 − 1)/(1.5 + 1))²
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  // No throughput cutoff: every branch down to max_depth 8 is traced.
  const auto clear = test::load(slabScene("[1,1,1]", 8));
  EXPECT_NEAR(clear.trace(ray, 0).r, slabAtDepthLimit(R, 1, 8), 1e-6);
  // With Beer: a = (0.5, 0.8, 1) per unit over d = 0.5 → A = a^0.5 per crossing.
  const auto tinted = test::load(slabScene("[0.5,0.8,1]", 8));
  const Rgb L = tinted.trace(ray, 0);
  // Each crossing starts a few ulps of 0.25 inside the slab; the direct path dominates the sum.
  const double beerTol = std::fabs(std::log(0.5)) * spawnOffset(0.25f) * 1.1;
  EXPECT_NEAR(L.r, slabAtDepthLimit(R, std::sqrt(0.5), 8), beerTol);
  EXPECT_NEAR(L.g, slabAtDepthLimit(R, std::sqrt(0.8), 8), beerTol);
  EXPECT_NEAR(L.b, slabAtDepthLimit(R, 1, 8), 1e-6);
  // At max_depth 2 the ray reflected inside at the back face (depth 2) meets the front face,
  // and both its children return the background: L = (1 − R)² + (1 − R)·R = 1 − R.
  EXPECT_NEAR(test::load(slabScene("[1,1,1]", 2)).trace(ray, 0).r, 1 - R, 1e-6);
}

TEST(Shading, AHollowCsgShellAbsorbsOnlyInItsGlassAndHoldsAnotherMedium) {
  // A CSG shell (a sphere of radius 1 minus one of 0.8, attenuation a = (0.5, 0.5, 1)) with a
  // separate glass ball of radius 0.5 (a = (0.8, 1, 1)) in its cavity, all index-matched (η = 1:
  // no reflection, no bending). The ray through the centre crosses 0.2 + 0.2 of shell glass, the
  // cavity's air twice (0.3 each: the shell's inner surface is left, not entered), and 1.0 of
  // the ball inside the shell's cavity: L = 0.5^0.4 · 0.8 in red, 0.5^0.4 in green, 1 in blue.
  // Counting the cavity as shell glass would give 0.5^1.0 in green.
  const auto t = load(R"("render": {"background": [1,1,1], "max_depth": 12},
    "materials": {"shell": {"type": "dielectric", "ior": 1, "attenuation": [0.5,0.5,1]},
                  "ball": {"type": "dielectric", "ior": 1, "attenuation": [0.8,1,1]}},
    "objects": [{"type": "csg", "op": "difference", "material": "shell", "operands": [
                   {"type": "sphere", "center": [0,0,-5], "radius": 1},
                   {"type": "sphere", "center": [0,0,-5], "radius": 0.8}]},
                {"type": "sphere", "center": [0,0,-5], "radius": 0.5, "material": "ball"}])");
  const Rgb L = t.trace({{0, 0, 0}, {0, 0, -1}});
  // Six entries, each a few ulps of 5 short (spawnOffset): Beer's factor errs by |ln a| times it.
  const double tol = 6 * std::fabs(std::log(0.5)) * spawnOffset(6.0f);
  EXPECT_NEAR(L.r, std::pow(0.5, 0.4) * 0.8, tol);
  EXPECT_NEAR(L.g, std::pow(0.5, 0.4), tol);
  EXPECT_NEAR(L.b, 1.0, 1e-6);
}

TEST(Shading, ThroughputCutoffChangesNoPixelByMoreThanItsBound) {
  // The cutoff drops branches whose weight is below 1/1024; behind them is radiance ≤ 1 here,
  // so the pixel moves by less than 1/1024 — on the slab it drops the rays of depth ≥ 4
  // (weight (1−R)R³ ≈ 6.1e-5) and keeps depth 3 ((1−R)R² ≈ 1.5e-3), whose refracted part
  // leaves: L = (1 − R)²(1 + R²).
  const auto clear = test::load(slabScene("[1,1,1]", 8));
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  const float exact = clear.trace(ray, 0).r;
  const float cut = clear.trace(ray).r;
  EXPECT_LE(std::fabs(exact - cut), kDefaultMinThroughput);
  EXPECT_NEAR(cut, 0.96 * 0.96 * (1 + 0.04 * 0.04), 1e-6);
}

TEST(Shading, GlassSlabWithAHighlight) {
  // The same slab with k_s = 0.5 (Blinn, p = 80) under a point light of intensity 2 on the
  // view axis at z = 2: at the front face l = v = n, so h = n and the highlight adds
  // k_s·I·1 = 1 to the slab's light. The back face's highlight is in the slab's shadow (opaque
  // shadows), and inside the slab the front face turns away from the light.
  const std::string light =
      R"(, "lights": [{"type": "point", "position": [0,0,2], "intensity": [2,2,2]}])";
  const auto t =
      test::load(slabScene("[1,1,1]", 8, R"(, "ks": [0.5,0.5,0.5], "exponent": 80)") + light);
  EXPECT_NEAR(t.trace({{0, 0, 5}, {0, 0, -1}}).r, 0.96 * 0.96 * (1 + 0.04 * 0.04) + 0.5 * 2, 1e-6);
}

TEST(Shading, MirrorWithAHighlight) {
  // A mirror (k_m 0.9) with k_s 0.25 facing a point light of intensity 2 on the view axis:
  // L = k_s·I + k_m × background, the reflected ray escaping to the background 0.5.
  const auto t = test::load(R"("render": {"background": [0.5,0.5,0.5]},
    "materials": {"m": {"type": "mirror", "km": [0.9,0.9,0.9], "ks": [0.25,0.25,0.25], "exponent": 40}},
    "lights": [{"type": "point", "position": [0,0,2], "intensity": [2,2,2]}],
    "objects": [{"type": "quad", "corner": [-1,-1,0], "edge1": [2,0,0], "edge2": [0,2,0], "material": "m"}])");
  EXPECT_NEAR(t.trace({{0, 0, 5}, {0, 0, -1}}).r, 0.25 * 2 + 0.9 * 0.5, 1e-6);
}

TEST(Shading, MirrorAtDepthLimitZeroShowsTheBackground) {
  // Seed 002 §9.1: Trace(r, d) returns the background colour for d > d_max, so a mirror seen
  // at max_depth 0 shows k_m × background, exactly.
  const auto t = test::load(R"("render": {"background": [0.5, 0.25, 1], "max_depth": 0},
    "materials": {"m": {"type": "mirror", "km": [0.9, 0.8, 0.7]}},
    "objects": [{"type": "quad", "corner": [-1,-1,0], "edge1": [2,0,0], "edge2": [0,2,0], "material": "m"},
                {"type": "quad", "corner": [-9,-9,9], "edge1": [18,0,0], "edge2": [0,18,0], "material": "m"}])");
  const Rgb L = t.trace({{0.3f, 0.2f, 5}, {0, 0, -1}});
  EXPECT_EQ(L.r, 0.9f * 0.5f);
  EXPECT_EQ(L.g, 0.8f * 0.25f);
  EXPECT_EQ(L.b, 0.7f * 1.0f);
}

TEST(Shading, NestedDielectricsUseTheSurroundingMedium) {
  // A glass sphere (1.5) inside a water sphere (1.33), both centred: at normal incidence the
  // glass interface reflects ((1.5 − 1.33)/(1.5 + 1.33))², not ((1.5 − 1)/(1.5 + 1))². Behind
  // them a surface emits 1; at max_depth 4 only the straight pass reaches it (the ray of
  // depth 4), so L = (1−R_w)²(1−R_g)²: every other path needs more depth and returns the
  // background, black.
  const auto t = load(R"("render": {"max_depth": 4},
    "materials": {"glass": {"type": "dielectric", "ior": 1.5},
                  "water": {"type": "dielectric", "ior": 1.33},
                  "lamp": {"type": "phong", "kd": [0,0,0], "ke": [1,1,1]}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 2, "material": "water"},
                {"type": "sphere", "center": [0,0,0], "radius": 1, "material": "glass"},
                {"type": "quad", "corner": [-50,-50,-8], "edge1": [100,0,0], "edge2": [0,100,0], "material": "lamp"}])");
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

// A Lambert floor (k_d = 1) at y = 0 lit from straight above by a point light of intensity 1
// at y = 6, seen from straight above: unshadowed it reads 1. `media` are the dielectric boxes
// around it, in the order listed; shadows are transparent.
std::string floorInside(const std::string& materials, const std::string& media) {
  return R"("render": {"transparent_shadows": true},
    "materials": {"floor": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}, )" +
         materials + R"(},
    "lights": [{"type": "point", "position": [0,6,0], "intensity": [1,1,1]}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "floor"}, )" +
         media + "]";
}

TEST(Shading, ATransparentShadowThatMeetsNothingIsOneRayWithAllTheLight) {
  // Glass beside the shadow ray's path, not on it: the ray from the floor to the light meets
  // nothing and brings the whole light (the floor reads 1, as unshadowed), and it is one ray:
  // with the camera ray, two (the production kernel finds such rays in a coherent stream).
  const auto t =
      load(floorInside(R"("glass": {"type": "dielectric", "ior": 1.5})",
                       R"({"type": "box", "min": [3,0,3], "max": [4,1,4], "material": "glass"})"));
  const Ray ray{{0, 5, 0}, {0, -1, 0}};
  EXPECT_EQ(t.trace(ray).r, 1.0f);
  const Sampler sampler(SamplerKind::Stratified, 1, 0);
  RayCounters counters;
  const Radiance r = BatchedKernel(t.scene, *t.accel, kDefaultMinThroughput, 1)
                         .trace(ray, SampleKey(&sampler, 0, 0, 0), counters);
  EXPECT_EQ(counters.shadow, 1u);
  EXPECT_EQ(r.rays, 2u);
}

TEST(Shading, FloorUnderWaterIsLitThroughIt) {
  // Two units of water above the floor (a = 0.5 per unit, ior 1, so no Fresnel): the light
  // crosses them on its way down and again on its way up to the eye, 0.5²·0.5² = 0.0625. The
  // shadow ray starts inside the water, with the interior list of the ray that reached the
  // floor. Each crossing may be shortened by a spawn offset at y = 2 (spawnOffset).
  const auto t = load(
      floorInside(R"("water": {"type": "dielectric", "ior": 1, "attenuation": [0.5,0.5,0.5]})",
                  R"({"type": "box", "min": [-9,-1,-9], "max": [9,2,9], "material": "water"})"));
  EXPECT_NEAR(t.trace({{0, 5, 0}, {0, -1, 0}}).r, 0.0625,
              0.0625 * std::log(2.0) * 2 * spawnOffset(2.0f) * 1.1);
}

TEST(Shading, ShadowRaysLeaveNestedMediaThroughTheirIndices) {
  // The floor in water (1.33) inside a glass block (1.5), no absorption, everything at normal
  // incidence: the light crosses air→glass and glass→water, the eye's ray the same, so
  // L = (1 − R_ag)²(1 − R_gw)². The shadow ray leaves the water into glass (not into air) and
  // then the glass into air. Fainter paths fall under the throughput cutoff.
  const auto t =
      load(floorInside(R"("water": {"type": "dielectric", "ior": 1.33},
                                     "glass": {"type": "dielectric", "ior": 1.5})",
                       R"({"type": "box", "min": [-9,-2,-9], "max": [9,2,9], "material": "glass"},
                                     {"type": "box", "min": [-8,-1,-8], "max": [8,1,8], "material": "water"})"));
  const double Rag = 0.04, Rgw = std::pow(0.17 / 2.83, 2);
  EXPECT_NEAR(t.trace({{0, 5, 0}, {0, -1, 0}}).r, std::pow(1 - Rag, 2) * std::pow(1 - Rgw, 2),
              1e-6);
}

TEST(Shading, EmissionIsSeenDirectlyAndInAMirror) {
  // A surface with k_e (seed 002 §9.1's own emission) shows k_e to a ray that meets it, and a
  // mirror (k_m = 0.5) in front of it shows k_m·k_e; emission lights nothing else.
  const auto t = load(R"("materials": {
      "lamp": {"type": "phong", "kd": [0,0,0], "ke": [4,3.5,3]},
      "chrome": {"type": "mirror", "km": [0.5,0.5,0.5]}},
    "objects": [{"type": "quad", "corner": [-1,-1,-2], "edge1": [2,0,0], "edge2": [0,2,0], "material": "lamp"},
                {"type": "quad", "corner": [2,-1,0], "edge1": [0,0,-2], "edge2": [0,2,0], "material": "chrome"}])");
  const Rgb direct = t.trace({{0, 0, 5}, {0, 0, -1}});
  EXPECT_EQ(direct, (Rgb{4, 3.5f, 3}));
  // The mirror is the plane x = 2; a ray from (0, 0, 1) to (2, 0, −1) reflects to (0, 0, −3)
  // and meets the lamp at z = −2 on the way.
  const Rgb mirrored = t.trace(rayTo({0, 0, 1}, {2, 0, -1}));
  EXPECT_NEAR(mirrored.r, 2, 1e-6);
  EXPECT_NEAR(mirrored.g, 1.75, 1e-6);
  EXPECT_NEAR(mirrored.b, 1.5, 1e-6);
}

// A quad light of intensity 2 and area 4 facing down (edge1 × edge2 = −4y) at y = 3, visible.
std::string visibleLight(const char* emission) {
  return std::string(R"("materials": {"chrome": {"type": "mirror", "km": [0.5,0.5,0.5]}},
    "lights": [{"type": "quad", "corner": [-1,3,-1], "edge1": [2,0,0], "edge2": [0,0,2],
                "intensity": [2,2,2], "samples": 4, "visible": true, "emission": ")") +
         emission + R"("}],
    "objects": [{"type": "quad", "corner": [-5,0,-5], "edge1": [0,0,10], "edge2": [10,0,0], "material": "chrome"}])";
}

TEST(Shading, VisibleAreaLightsShowTheirRadiance) {
  // Radiance mode: the light shows its intensity from below (its emitting side), black from
  // above; and in a mirror (k_m = 0.5) half of it.
  const auto radiance = load(visibleLight("radiance"));
  EXPECT_EQ(radiance.trace({{0, 1, 0}, {0, 1, 0}}).r, 2.0f);
  EXPECT_EQ(radiance.trace({{0, 5, 0}, {0, -1, 0}}).r, 0.0f);  // the back; the mirror is hidden
  EXPECT_EQ(radiance.trace(rayTo({0.2f, 1, 0}, {0, 0, 0})).r, 1.0f);
  // Seed mode: intensity / area = 0.5 from both sides.
  const auto seed = load(visibleLight("seed"));
  EXPECT_EQ(seed.trace({{0, 1, 0}, {0, 1, 0}}).r, 0.5f);
  EXPECT_EQ(seed.trace({{0, 5, 0}, {0, -1, 0}}).r, 0.5f);
}

TEST(Shading, AVisibleLightDoesNotShadowItsOwnLight) {
  // The light's own surface must not block its shadow rays: a floor lit by it reads the same,
  // bit for bit, whether the light is visible or not.
  for (const char* emission : {"seed", "radiance"}) {
    const std::string floor = R"(,
      "materials": {"m": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}},
      "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}])";
    const auto light = [&](bool visible) {
      return std::string(R"("lights": [{"type": "quad", "corner": [-1,3,-1], "edge1": [2,0,0],
        "edge2": [0,0,2], "intensity": [2,2,2], "samples": 16, "emission": ")") +
             emission + R"(", "visible": )" + (visible ? "true" : "false") + "}]";
    };
    const auto hidden = load(light(false) + floor), shown = load(light(true) + floor);
    for (const Vec3f target : {Vec3f{0, 0, 0}, Vec3f{0.7f, 0, -0.3f}, Vec3f{3, 0, 2}}) {
      const Ray ray = rayTo({0.1f, 2, 0.2f}, target);
      const float a = hidden.trace(ray).r, b = shown.trace(ray).r;
      EXPECT_GT(a, 0.0f) << emission;
      EXPECT_EQ(a, b) << emission << ": the light's surface shadows its own light";
    }
  }
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
  const BatchedKernel integrator(s, *accel, 0, s.render.spp);
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
    test::Traced t{test::sceneFromText(R"({"render": {"ambient": [1,1,1]},
      "camera": {"eye": )" + at(c.y) + R"(, "look_at": )" +
                                       at(0) + R"(, "up": [0,0,-1]},
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
