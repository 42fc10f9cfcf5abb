// Distribution effects (seed 000 §13.4) against closed forms, with tolerances from the
// estimator's variance and fixed seeds.
#include <gtest/gtest.h>

#include "integrator/batched_kernel.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

struct LoadedScene {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
};

LoadedScene load(const std::string& text) {
  LoadedScene s{test::sceneFromText(text), nullptr};
  s.accel = makeAccelerator(AccelKind::Embree, s.scene);
  return s;
}

Film render(const LoadedScene& s) {
  RenderOptions opt;
  opt.progress = false;
  return renderScene(s.scene, *s.accel, opt).film;
}

// A Lambert floor (k_d = 1, so the pixel reads the irradiance E) under one light.
std::string floorUnder(const std::string& light, int samples) {
  return R"({"camera": {"eye": [0,5,0.001], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}},
    "lights": [)" +
         light + R"(, "samples": )" + std::to_string(samples) + R"(}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}]})";
}

// Estimate of E at the origin from camera sample `index` of pixel (px, 0).
float irradianceAtOrigin(const LoadedScene& s, int px) {
  const Sampler sampler(SamplerKind::Stratified, 1, 11);
  RayCounters counters;
  return BatchedKernel(s.scene, *s.accel, kDefaultMinThroughput, s.scene.render.spp)
      .trace({{0, 1, 0}, {0, -1, 0}}, SampleKey{&sampler, px, 0, 0}, counters)
      .L.r;
}

TEST(AreaLights, DiskInRadianceModeMatchesOnAxisIrradiance) {
  // Disk of radius R at height h facing down, radiance L: E = πL·R²/(h² + R²) on the axis.
  // One light sample is f(y) = L·A·h²/r⁴ (both cosines are h/r); its variance, integrated
  // numerically below, bounds the stratified estimator's: |error| ≤ 3σ = 3√(Var f / N).
  const double R = 1, h = 2, L = 3, A = kPi * R * R;
  const double exact = kPi * L * R * R / (h * h + R * R);
  double m1 = 0, m2 = 0;
  constexpr int kQ = 2000;  // radial quadrature of E[f] and E[f²] over the uniform disk
  for (int i = 0; i < kQ; ++i) {
    const double rho = R * (i + 0.5) / kQ, w = 2 * rho / (R * R) * (R / kQ);
    const double f = L * A * h * h / std::pow(h * h + rho * rho, 2);
    m1 += w * f;
    m2 += w * f * f;
  }
  ASSERT_NEAR(m1, exact, 1e-6 * exact);  // the quadrature itself reproduces E
  const double var = m2 - m1 * m1;
  std::vector<double> rmsErrors;
  for (int n : {4, 16, 64, 256}) {
    const LoadedScene s = load(floorUnder(R"({"type": "disk", "center": [0,2,0], "normal": [0,-1,0],
        "radius": 1, "intensity": [3,3,3], "emission": "radiance")",
                                          n));
    double sq = 0;
    constexpr int kPixels = 32;  // independent shuffles of the light's sample set
    for (int px = 0; px < kPixels; ++px) {
      const double e = irradianceAtOrigin(s, px) - exact;
      EXPECT_LE(std::fabs(e), 3 * std::sqrt(var / n)) << "N = " << n << ", pixel " << px;
      sq += e * e;
    }
    rmsErrors.push_back(std::sqrt(sq / kPixels));
  }
  // Log-log slope of RMS error against N over 4 levels (×4 each): at least as steep as −0.5.
  const double slope = std::log(rmsErrors.back() / rmsErrors.front()) / std::log(64.0);
  EXPECT_LE(slope, -0.5);
}

// Irradiance from a Lambertian polygon of radiance L at point x with normal n (Lambert's
// formula): E = L/2 · Σ Θ_i (n · Γ_i), Θ_i the angle the edge subtends, Γ_i its unit normal.
double polygonIrradiance(const std::vector<Vec3f>& poly, Vec3f x, Vec3f n, double L) {
  double sum = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3f a = normalize(poly[i] - x), b = normalize(poly[(i + 1) % poly.size()] - x);
    const double theta = std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0));
    sum += theta * dot(n, normalize(cross(a, b)));
  }
  return 0.5 * L * std::fabs(sum);
}

TEST(AreaLights, QuadInRadianceModeMatchesPolygonFormFactor) {
  const std::vector<Vec3f> quad = {
      {-0.5f, 1.5f, -1}, {1.5f, 1.5f, -1}, {1.5f, 1.5f, 0}, {-0.5f, 1.5f, 0}};
  const double exact = polygonIrradiance(quad, {0, 0, 0}, {0, 1, 0}, 2);
  // corner + edge1 × edge2 = (2,0,0) × (0,0,1) = (0,−2,0): emits downwards.
  const LoadedScene s =
      load(floorUnder(R"({"type": "quad", "corner": [-0.5,1.5,-1], "edge1": [2,0,0],
      "edge2": [0,0,1], "intensity": [2,2,2], "emission": "radiance")",
                      256));
  // f ≤ L·A·cos²/r² ≤ 2·2/1.5² ≈ 1.8, so σ_f < 1.8 and 3σ at N = 256 is below 0.34; the
  // stratified estimate is far tighter, so a bound of 3·1.8/√256 is safe and still meaningful
  // next to E ≈ 0.8.
  for (int px = 0; px < 16; ++px) EXPECT_NEAR(irradianceAtOrigin(s, px), exact, 3 * 1.8 / 16) << px;
  double mean = 0;
  for (int px = 0; px < 64; ++px) mean += irradianceAtOrigin(s, px) / 64;
  EXPECT_NEAR(mean, exact, 3 * 1.8 / std::sqrt(256.0 * 64));
}

TEST(AreaLights, ShrunkenSeedQuadConvergesToThePointLight) {
  // Seed mode: the average of point lights over the area. At 10⁻³ × 10⁻³ it must match a
  // point light at its centre to 1e-4 over a whole image with shadows and speculars: the
  // mean of the 4 stratified points (one per 5e-4 cell) lies within 2.5e-4 of the centre per
  // axis, and at distance ≥ 2 a lit point's k_d·cosθ (0.7) and highlight (k_s 0.3, exponent
  // 20, whose cosine moves by half the angle) move by at most 0.35·|Δ| and 0.3·20·0.25·|Δ|,
  // 1e-4 in all to first order. (Measured: 2.9e-5.)
  const std::string scene = R"({"render": {"width": 24, "height": 16, "spp": 2},
    "camera": {"eye": [0,2,4], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong", "kd": [0.7,0.7,0.7], "ks": [0.3,0.3,0.3], "exponent": 20}},
    "lights": [LIGHT],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"},
                {"type": "sphere", "center": [0,0.5,0], "radius": 0.5, "material": "m"}]})";
  const auto with = [&](const std::string& light) {
    std::string t = scene;
    t.replace(t.find("LIGHT"), 5, light);
    return render(load(t));
  };
  const Film point = with(R"({"type": "point", "position": [1,3,1], "intensity": [1,1,1]})");
  const Film quad = with(R"({"type": "quad", "corner": [0.9995,3,0.9995], "edge1": [0.001,0,0],
      "edge2": [0,0,0.001], "intensity": [1,1,1], "samples": 4})");
  double maxDiff = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x)
      maxDiff = std::max(maxDiff, std::fabs(double(point.pixel(x, y)[0]) - quad.pixel(x, y)[0]));
  EXPECT_LE(maxDiff, 1e-4);
}

TEST(AreaLights, PenumbraWidthMatchesGeometry) {
  // A quad light 2 wide (x ∈ [−1, 1], long in z) at height H = 4 and an occluding half-plane
  // (x < 0) at height h = 2: by similar triangles the floor sees the whole light for x ≥ 1,
  // none of it for x ≤ −1, and part of it in between — a penumbra w·h/(H − h) = 2 wide. The
  // orthographic view, from y = 1 below the occluder, is 8 units over 64 px (8 px per unit):
  // umbra and full light must start within a pixel of x = ∓1.
  const std::string head = R"({"render": {"width": 64, "height": 2, "spp": 4},
    "camera": {"type": "orthographic", "eye": [0,1,0], "look_at": [0,0,0], "up": [0,0,-1], "height": 0.25},
    "materials": {"m": {"type": "phong", "kd": [1,1,1], "ka": [0,0,0]}},
    "lights": [{"type": "quad", "corner": [-1,4,-20], "edge1": [2,0,0], "edge2": [0,0,40], "samples": 64}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"})";
  const Film open = render(load(head + "]}"));
  const Film shadowed = render(load(head + R"(, {"type": "quad", "corner": [-30,2,-30],
      "edge1": [30,0,0], "edge2": [0,0,60], "material": "m"}]})"));
  for (int x = 0; x < 64; ++x) {
    const double u = -4 + (x + 0.5) / 8;  // pixel centre; pixels span ±1/16
    const double v = shadowed.pixel(x, 0)[0], lit = open.pixel(x, 0)[0];
    if (u < -1 - 0.125) {
      EXPECT_EQ(v, 0.0) << "umbra at u = " << u;
    }
    if (u > 1 + 0.125) {
      EXPECT_EQ(v, lit) << "full light at u = " << u;
    }
    if (std::fabs(u) < 1 - 0.125) {
      EXPECT_GT(v, 0.0) << "penumbra at u = " << u;
      EXPECT_LT(v, lit) << "penumbra at u = " << u;
    }
  }
}

std::string kSquareLens(double halfWidth) {
  return "\"aperture_radius\": " + std::to_string(halfWidth) + ", \"lens\": \"square\"";
}

// A white half-plane (x ≥ 0, ambient 1 so it reads exactly 1) at depth z0 on black, seen
// through a square lens of half-width a focused at f: the edge spreads into a linear ramp
// 2a·|z0 − f|/z0 wide on the focus plane (seed 000 §13.4.3, similar triangles).
Film edgeThroughLens(double z0, const std::string& lens) {
  return render(load(R"({"render": {"width": 64, "height": 4, "spp": 1024, "ambient": [1,1,1]},
    "camera": {"eye": [0,0,0], "look_at": [0,0,-1], "vfov": 90, "focus_distance": 2, )" +
                     lens + R"(},
    "materials": {"white": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "quad", "corner": [0,-100,)" +
                     std::to_string(-z0) + R"(],
                 "edge1": [100,0,0], "edge2": [0,200,0], "material": "white"}]})"));
}

TEST(DepthOfField, ApertureZeroIsThePinholeBitForBit) {
  EXPECT_EQ(edgeThroughLens(4, kSquareLens(0)).toFloatRgba(),
            render(load(R"({"render": {"width": 64, "height": 4, "spp": 1024, "ambient": [1,1,1]},
    "camera": {"eye": [0,0,0], "look_at": [0,0,-1], "vfov": 90},
    "materials": {"white": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "quad", "corner": [0,-100,-4], "edge1": [100,0,0], "edge2": [0,200,0],
                 "material": "white"}]})"))
                .toFloatRgba());
}

TEST(DepthOfField, FocusPlaneStaysSharp) {
  // The edge on the focus plane (z0 = f = 2) falls on the boundary of columns 31 and 32.
  const Film f = edgeThroughLens(2, kSquareLens(4));
  EXPECT_EQ(f.pixel(31, 1)[0], 0.0);
  EXPECT_EQ(f.pixel(32, 1)[0], 1.0);
}

TEST(DepthOfField, CircleOfConfusionMatchesTheThinLens) {
  // vfov 90°, height 4 px: one pixel is f·2/4 = 1 unit wide on the focus plane at f = 2.
  // z0 = 4, a = 4: ramp width 2·4·|4 − 2|/4 = 4 units = 4 px, centred on column 32. Box-filtered
  // pixels on a linear ramp read its value at their centres: 0.125, 0.375, 0.625, 0.875.
  // 1024 stratified samples per pixel: σ < 0.5/√1024 ≈ 0.016 even unstratified; 0.03 is ~2σ of
  // that bound and far more than the stratified spread.
  const Film f = edgeThroughLens(4, kSquareLens(4));
  const double expected[] = {0.125, 0.375, 0.625, 0.875};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f.pixel(30 + i, 1)[0], expected[i], 0.03) << 30 + i;
  EXPECT_EQ(f.pixel(27, 1)[0], 0.0);  // outside the ramp: untouched
  EXPECT_EQ(f.pixel(36, 1)[0], 1.0);
}

TEST(Gloss, GlossyMirrorBlursButKeepsTheMeanOfAUniformBackground) {
  // Facing a uniform background, every glossy ray that stays above the surface sees the same
  // radiance: at normal incidence with gloss 0.5 no perturbed ray goes below, so the pixel is
  // k_m × background exactly, as for the ideal mirror; a grazing view loses the rays that dip
  // below the surface (they return black), so it reads less than k_m × background.
  const auto pixelAt = [](const char* gloss, const char* eye) {
    const LoadedScene s = load(
        std::string(R"({"render": {"width": 1, "height": 1, "spp": 64, "background": [0.5,0.5,0.5]},
      "camera": {"eye": )") +
        eye + R"(, "look_at": [0,0,0], "vfov": 1},
      "materials": {"m": {"type": "mirror", "km": [0.8,0.8,0.8], "gloss": )" +
        gloss + R"(}},
      "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}]})");
    return render(s).pixel(0, 0)[0];
  };
  EXPECT_NEAR(pixelAt("0.5", "[0,3,0.0001]"), 0.4, 1e-6);
  EXPECT_NEAR(pixelAt("0", "[0,3,0.0001]"), 0.4, 1e-6);
  EXPECT_EQ(pixelAt("0", "[3,0.1,0]"), 0.4f);
  // Viewed 1.9° above the surface, r rises sin 1.9° = 0.0333 above it; a square of width 1 in
  // r's tangent frame (one tangent within 2° of the normal) pushes a perturbed ray below when
  // its offset along that tangent is under −0.0333: a share p = 0.5 − 0.0333 of the square.
  // The pixel reads k_m·background·(1 − p) = 0.2133; 64 samples of a loss of probability p
  // have σ ≤ 0.4·√(p(1 − p)/64) = 0.025 even unstratified: within 3σ.
  const double lost = 0.5 - std::sin(std::atan2(0.1, 3.0));
  EXPECT_NEAR(pixelAt("1.0", "[3,0.1,0]"), 0.4 * (1 - lost),
              3 * 0.4 * std::sqrt(lost * (1 - lost) / 64));
}

// Seed 002 §9.3 with a photographer's lens: focal length F = 1, aperture number a = 1/8, so the
// lens diameter is D = F/a = 8 (eq. 9.23). Focused at P = 2, the film sits at K' = 1/(1/F − 1/P)
// = 2; the edge at T = 4 comes to focus at K = 1/(1/F − 1/T) = 4/3 (eq. 9.24), so its points
// spread over circles of radius r = (D/2)·|K − K'|/K = 2 on the film (eq. 9.25 gives D·|K −
// K'|/K, the circle's diameter). The film is 2K'·tan 45° = 4 high over 4 pixels: r = 2 pixels.
// A disk blurs the edge into the disk's edge-spread function E(s) = ½ + (s·√(r² − s²)/r² +
// asin(s/r))/π; a pixel reads its mean over the pixel's width.
TEST(DepthOfField, APhotographersLensBlursByTheSeedsCircleOfConfusion) {
  const double F = 1, a = 0.125, P = 2, T = 4;
  const double D = F / a, filmDistance = 1 / (1 / F - 1 / P), focus = 1 / (1 / F - 1 / T);
  const double r = D / 2 * std::fabs(focus - filmDistance) / focus;  // on the film
  const double pixels = 4 / (2 * filmDistance * std::tan(kPi / 4));  // per unit of film
  const double radius = r * pixels;
  ASSERT_NEAR(radius, 2.0, 1e-12);
  const auto spread = [&](double s) {
    if (s <= -radius) return 0.0;
    if (s >= radius) return 1.0;
    const double q = s / radius;
    return 0.5 + (q * std::sqrt(1 - q * q) + std::asin(q)) / kPi;
  };
  const Film f = edgeThroughLens(T, "\"focal_length\": 1, \"f_number\": 0.125");
  for (int column = 29; column <= 34; ++column) {
    double mean = 0;  // over the pixel's width, midpoint rule
    for (int k = 0; k < 1000; ++k) mean += spread(column - 32 + (k + 0.5) / 1000) / 1000;
    // 1024 samples: as in CircleOfConfusionMatchesTheThinLens, σ < 0.016 even unstratified.
    EXPECT_NEAR(f.pixel(column, 1)[0], mean, 0.03) << column;
  }
  EXPECT_EQ(f.pixel(27, 1)[0], 0.0);  // outside the circle's reach: untouched
  EXPECT_EQ(f.pixel(36, 1)[0], 1.0);
  // The same lens given by its radius F/(2a) = 4 is the same camera, bit for bit.
  EXPECT_EQ(f.toFloatRgba(), edgeThroughLens(T, "\"aperture_radius\": 4").toFloatRgba());
}

}  // namespace
}  // namespace glint
