// Gloss and blurred translucency distributed by seed 002 §9.3's specular distribution function,
// the Phong lobe cosⁿ α: an edge seen through the lobe against the profile the lobe predicts,
// computed here by quadrature, with tolerances from the estimator's variance at a fixed seed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

constexpr int kWidth = 64;
constexpr int kSpp = 4096;
constexpr double kHalfWidth = 0.8;  // the window spans x in [−0.8, 0.8]
constexpr double kExponent = 20;

// The share of the normalised lobe (n + 1)/(2π)·cosⁿ α about +y whose rays, leaving a point at
// x, meet the plane one unit away on its bright half x' > 0: x + tan α·cos φ > 0. For each α
// the share of φ is acos(−x / tan α)/π (clamped); the lobe's density of μ = cos α is
// (n + 1)·μⁿ, integrated by the midpoint rule over μ.
double brightShare(double x, double n) {
  constexpr int kSteps = 4000;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = (i + 0.5) / kSteps;
    const double tanA = std::sqrt(1 - mu * mu) / mu;
    const double c = std::clamp(-x / tanA, -1.0, 1.0);
    sum += (n + 1) * std::pow(mu, n) * std::acos(c) / kPi;
  }
  return sum / kSteps;
}

// The same for seed 000's square of width a about +y: the ray's offset on the plane is
// a·(u − ½) along x (its tangent frame's first axis is +x), uniform, so the share is a ramp.
double squareShare(double x, double a) { return std::clamp(0.5 + x / a, 0.0, 1.0); }

// Column `i`'s expected value: k times the share, averaged over the pixel's width (the camera
// samples cover it uniformly), by the midpoint rule.
template <class Share>
double pixelMean(int i, double k, Share share) {
  const double pixel = 2 * kHalfWidth / kWidth;
  double sum = 0;
  for (int j = 0; j < 40; ++j) sum += share(-kHalfWidth + pixel * (i + (j + 0.5) / 40));
  return k * sum / 40;
}

// An orthographic camera looking straight down at a surface through the plane y = 0, its
// window 64 pixels wide across x ∈ [−0.8, 0.8]: every camera ray is vertical, so the ideal
// reflected (or ior-1 refracted) ray is ±y, and the lobe spreads it onto a bright half-plane
// one unit away, x > 0, that emits 1.
std::string edgeScene(const std::string& sampler, const std::string& material, double emitterY,
                      double eyeY) {
  const std::string y = std::to_string(emitterY);
  return R"({"render": {"width": 64, "height": 1, "spp": 4096, "seed": 3, "max_depth": 2,
      "sampler": ")" +
         sampler + R"("},
    "camera": {"type": "orthographic", "eye": [0, )" +
         std::to_string(eyeY) + R"(, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
               "window": [-0.8, 0.8, -0.0125, 0.0125]},
    "materials": {"surface": )" +
         material + R"(,
      "bright": {"type": "phong", "kd": [0, 0, 0], "ke": [1, 1, 1]}},
    "objects": [
      {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "surface"},
      {"type": "quad", "corner": [0, )" +
         y + R"(, -1000], "edge1": [1000, 0, 0], "edge2": [0, 0, 2000],
       "material": "bright"}]})";
}

std::vector<float> renderRow(const std::string& text) {
  const Scene scene = test::sceneFromText(text);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  const Film film = renderScene(scene, *accel, opt).film;
  std::vector<float> row;
  for (int i = 0; i < kWidth; ++i) row.push_back(static_cast<float>(film.pixel(i, 0)[0]));
  return row;
}

// Each sample is k or 0 (the ray meets the bright half or not), with probability the pixel's
// share p: the mean of 4096 has σ ≤ k·√(p(1 − p)/4096) even unstratified. Allowed: 4σ, plus
// 1e-3 for the quadrature. Returns the columns outside it.
int columnsOff(const std::vector<float>& row, const std::vector<double>& expected, double k) {
  int off = 0;
  for (int i = 0; i < kWidth; ++i) {
    const double p = std::clamp(expected[i] / k, 0.0, 1.0);
    const double tolerance = 4 * k * std::sqrt(p * (1 - p) / kSpp) + 1e-3;
    off += std::fabs(row[i] - expected[i]) > tolerance;
  }
  return off;
}

std::vector<double> lobeProfile(double k) {
  std::vector<double> out;
  for (int i = 0; i < kWidth; ++i)
    out.push_back(pixelMean(i, k, [](double x) { return brightShare(x, kExponent); }));
  return out;
}

TEST(SpecularDistribution, GlossyMirrorReflectsAnEdgeByThePhongLobesProfile) {
  // A mirror of k_m 0.8 with "gloss": {"phong": 20} under the bright half-plane at y = 1: each
  // column reads k_m × the lobe-weighted mean of what its rays see, 0.8 × brightShare, under
  // every sampler. The lobe about +y never dips below the surface.
  const std::vector<double> expected = lobeProfile(0.8);
  ASSERT_LT(expected.front(), 0.05);  // the window holds the whole edge, tails included
  ASSERT_GT(expected.back(), 0.75);
  for (const char* sampler : {"stratified", "random", "regular", "sobol"}) {
    const std::vector<float> row = renderRow(edgeScene(
        sampler, R"({"type": "mirror", "km": [0.8, 0.8, 0.8], "gloss": {"phong": 20}})", 1, 0.5));
    EXPECT_EQ(columnsOff(row, expected, 0.8), 0) << sampler;
  }
}

TEST(SpecularDistribution, TheSquareOfTheSameWidthGivesAnotherProfile) {
  // Seed 000's square, as wide as the lobe between its quartiles (the ramp 0.5 + x/a reaches
  // 0.75 where the lobe's profile does), blurs the edge into a ramp without the lobe's tails:
  // the lobe's profile check above refuses it, while it matches its own ramp.
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (brightShare(mid, kExponent) < 0.75 ? lo : hi) = mid;
  }
  const double a = 4 * lo;
  ASSERT_NEAR(a, 0.599, 0.001);
  const std::vector<float> row = renderRow(edgeScene(
      "stratified",
      R"({"type": "mirror", "km": [0.8, 0.8, 0.8], "gloss": )" + std::to_string(a) + "}", 1, 0.5));
  EXPECT_GE(columnsOff(row, lobeProfile(0.8), 0.8), 8);
  std::vector<double> ramp;
  for (int i = 0; i < kWidth; ++i)
    ramp.push_back(pixelMean(i, 0.8, [a](double x) { return squareShare(x, a); }));
  EXPECT_EQ(columnsOff(row, ramp, 0.8), 0);
}

TEST(SpecularDistribution, BlurredTranslucencySpreadsTheRefractedRayByTheLobe) {
  // A dielectric of index 1 with seed 002's k_t = 0.7 and "blur": {"phong": 20}: the refracted
  // ray is the camera ray itself (−y), spread by the lobe onto the bright half-plane one unit
  // below; nothing is reflected (fresnel none, k_m black), so each column reads k_t ×
  // brightShare.
  const std::vector<float> row = renderRow(
      edgeScene("stratified",
                R"({"type": "dielectric", "ior": 1, "fresnel": "none", "kt": [0.7, 0.7, 0.7],
          "blur": {"phong": 20}})",
                -1, 0.5));
  EXPECT_EQ(columnsOff(row, lobeProfile(0.7), 0.7), 0);
}

}  // namespace
}  // namespace glint
