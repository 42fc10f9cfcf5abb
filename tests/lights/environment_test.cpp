// The environment light (lights/environment.h) on its own: the orientation of its lat-long
// image, its sampling distribution (a density over the sphere that integrates to 1, follows
// luminance, and agrees with the estimates its samples carry), and why it is sampled so: a sun
// that a uniform choice of directions would rarely find.
#include "lights/environment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lights/light.h"

namespace glint {
namespace {

// A width × height image, black except where `texel` says.
LatLongImage image(int width, int height, Rgb (*texel)(int x, int y)) {
  LatLongImage im;
  im.width = width;
  im.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) im.texels.push_back(texel(x, y));
  return im;
}

// 8 × 2: four columns of φ, top and bottom; every texel a different colour (x + 1, y + 1, 0).
Rgb columnColour(int x, int y) { return {float(x + 1), float(y + 1), 0}; }

TEST(Environment, ImageOrientation) {
  // Row 0 looks along +Y; the centre (u = 0.5) along −Z; u = 0.75 along +X; u = 0 or 1 along
  // +Z; u = 0.25 along −X. Directions slightly above the horizon are in row 0, below in row 1.
  const EnvironmentLight env(image(8, 2, columnColour), 1, 0, 1);
  // Just right of the centre: u in (0.5, 0.625), column 4.
  EXPECT_EQ(env.radiance({0.1f, 0.1f, -1}), (Rgb{5, 1, 0}));
  EXPECT_EQ(env.radiance({-0.1f, -0.1f, -1}), (Rgb{4, 2, 0}));  // column 3, below
  EXPECT_EQ(env.radiance({1, 0.1f, 0.1f}), (Rgb{7, 1, 0}));     // +X, towards +Z: u > 0.75
  EXPECT_EQ(env.radiance({1, 0.1f, -0.1f}), (Rgb{6, 1, 0}));    // +X, towards −Z: u < 0.75
  EXPECT_EQ(env.radiance({0.1f, 0.1f, 1}), (Rgb{8, 1, 0}));     // +Z, right of the seam: u → 1
  EXPECT_EQ(env.radiance({-0.1f, 0.1f, 1}), (Rgb{1, 1, 0}));    // +Z, left of it: u → 0
  EXPECT_EQ(env.radiance({-1, 0.1f, -0.1f}), (Rgb{3, 1, 0}));   // −X, towards −Z: u > 0.25
  // The length of d does not matter.
  EXPECT_EQ(env.radiance({10, 1, -1}), (Rgb{6, 1, 0}));
}

TEST(Environment, RotationTurnsCounterClockwiseSeenFromAbove) {
  // 90° about +Y: what was seen along −Z (the centre, columns 3 and 4) is seen along −X, and
  // what was seen along +X (columns 5 and 6) along −Z.
  const EnvironmentLight env(image(8, 2, columnColour), 1, 90, 1);
  // A right-handed turn about +Y: (x, z) → (x cos α + z sin α, −x sin α + z cos α).
  EXPECT_EQ(env.radiance({-1, 0.1f, -0.1f}), (Rgb{5, 1, 0}));  // was (0.1, 0.1, −1)
  EXPECT_EQ(env.radiance({-1, 0.1f, 0.1f}), (Rgb{4, 1, 0}));   // was (−0.1, 0.1, −1)
  EXPECT_EQ(env.radiance({0.1f, 0.1f, -1}), (Rgb{7, 1, 0}));   // was (1, 0.1, 0.1)
  // −90° the other way: the centre is seen along +X.
  const EnvironmentLight back(image(8, 2, columnColour), 1, -90, 1);
  EXPECT_EQ(back.radiance({1, 0.1f, 0.1f}), (Rgb{5, 1, 0}));  // was (0.1, 0.1, −1)
}

TEST(Environment, IntensityScalesTheImage) {
  const EnvironmentLight env(image(8, 2, columnColour), 0.5f, 0, 1);
  EXPECT_EQ(env.radiance({0.1f, 0.1f, -1}), (Rgb{2.5f, 0.5f, 0}));
}

// A dim sky of 0.05 with a bright 2 × 2-texel sun of 2000 at rows 8-9 (about 42° above the
// horizon), columns 40-41, of 64 × 32.
Rgb sunAndSky(int x, int y) {
  return (x == 40 || x == 41) && (y == 8 || y == 9) ? Rgb{2000, 2000, 2000}
                                                    : Rgb{0.05f, 0.05f, 0.05f};
}

// The unit direction of image point (u, v) as the light maps it without rotation.
Vec3f directionOf(double u, double v) {
  const double theta = kPi * v, phi = 2 * kPi * (u - 0.5);
  return {float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
          float(-std::sin(theta) * std::cos(phi))};
}

TEST(Environment, ImageDensityIntegratesToOneAndFollowsLuminance) {
  const EnvironmentLight env(image(64, 32, sunAndSky), 1, 0, 1);
  // ∫ pdf dω over the sphere, a midpoint sum over 8 × 8 points per texel (dω = 2π² sin θ du dv;
  // the density is constant on each texel, so only the sin θ within a texel is approximated,
  // to about (Δθ)²/24 = 4e-4 relative).
  double total = 0;
  const int nu = 64 * 8, nv = 32 * 8;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = (i + 0.5) / nu, v = (j + 0.5) / nv;
      total += env.pdf({0, 1, 0}, directionOf(u, v)) * 2 * kPi * kPi * std::sin(kPi * v) /
               (double(nu) * nv);
    }
  EXPECT_NEAR(total, 1.0, 1e-3);
  // At texel centres (where sin θ is the row's) the density per steradian is luminance over
  // ∫ luminance dω: 2000 against 0.05.
  const float sun = env.pdf({0, 1, 0}, directionOf(40.5 / 64, 8.5 / 32));
  const float sky = env.pdf({0, 1, 0}, directionOf(10.5 / 64, 8.5 / 32));
  EXPECT_NEAR(sun / sky, 2000 / 0.05, 2000 / 0.05 * 1e-4);
}

TEST(Environment, SamplesCarryRadianceOverTheirDensity) {
  // Every sample's estimate is L(wi) / pdf(wi), with the same L and pdf the light reports for
  // its direction: the estimator's weights are the distribution's (float rounding, and sin θ
  // recomputed from the direction: 1e-3 relative).
  const EnvironmentLight env(image(64, 32, sunAndSky), 1, 30, 1);
  for (int k = 0; k < 64; ++k) {
    const Vec2f u{(float(k % 8) + 0.37f) / 8, (float(k / 8) + 0.61f) / 8};
    const EnvironmentSample s = env.sample({0, 1, 0}, u);
    EXPECT_NEAR(length(s.wi), 1, 1e-6);
    const float expected = env.radiance(s.wi).r / env.pdf({0, 1, 0}, s.wi);
    EXPECT_NEAR(s.radianceOverPdf.r, expected, expected * 1e-3) << k;
  }
}

TEST(Environment, DrawsSideBySideAreTheDrawsOneAtATime) {
  // The production kernel draws a point's samples in blocks (in lanes) and the reference
  // integrator one at a time; their images are equal only if every direction and value is the
  // same float. Blocks of 37 cross the block form's inner block and leave a partial lane; the
  // image has black texels and rows (zero-width cells) and u reaches 0 and just below 1, and 1
  // itself, which no sampler draws and the guide does not serve (each is searched whole).
  const EnvironmentLight env(
      image(64, 32,
            [](int x, int y) {
              return y % 5 == 0 || x % 7 == 0 ? Rgb{} : Rgb{float(x + 1), 0.5f, float(y)};
            }),
      0.7f, 30, 1);
  constexpr int kCount = 37;
  Vec2f u[kCount];
  EnvironmentSample block[kCount];
  for (int round = 0; round < 20; ++round) {
    for (int k = 0; k < kCount; ++k) {
      const int i = round * kCount + k;
      u[k] = {float((i * 37) % 101) / 101, float((i * 53) % 97) / 97};
    }
    if (round == 0) u[3] = {0x1.fffffep-1f, 0x1.fffffep-1f};
    if (round == 1) u[5] = {1, 0.5f}, u[12] = {0.25f, 1};
    env.sample({0, 1, 0}, u, kCount, block);
    for (int k = 0; k < kCount; ++k) {
      const EnvironmentSample one = env.sample({0, 1, 0}, u[k]);
      EXPECT_EQ(block[k].wi.x, one.wi.x) << round << " " << k;
      EXPECT_EQ(block[k].wi.y, one.wi.y) << round << " " << k;
      EXPECT_EQ(block[k].wi.z, one.wi.z) << round << " " << k;
      EXPECT_EQ(block[k].radianceOverPdf.r, one.radianceOverPdf.r) << round << " " << k;
      EXPECT_EQ(block[k].radianceOverPdf.g, one.radianceOverPdf.g) << round << " " << k;
      EXPECT_EQ(block[k].radianceOverPdf.b, one.radianceOverPdf.b) << round << " " << k;
    }
  }
}

TEST(Environment, ASunIsFoundWithFarLessVarianceThanByUniformDirections) {
  // The irradiance on an upward surface, E = ∫ L max(0, cos θ) dω, estimated per sample by
  // importance sampling (L/pdf · cos θ) and by uniform directions over the sphere (4π L cos θ),
  // with the same 4096 stratified points. The sun (2000 over 2 × 2 texels of a 64 × 32 image,
  // 0.029 sr at θ ≈ 48°: E_sun ≈ 2000 · 0.029 · cos 48° ≈ 38) is over 99 % of E (the sky gives
  // π · 0.05 = 0.16) but 0.23 % of the sphere: uniform directions find it about once in 440,
  // and their variance is all its; importance sampling draws it in proportion. Its per-sample
  // variance must be under a hundredth of the uniform one's.
  const EnvironmentLight env(image(64, 32, sunAndSky), 1, 0, 1);
  const Vec3f up{0, 1, 0};
  const int n = 64;
  double sumI = 0, sumI2 = 0, sumU = 0, sumU2 = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2f u{(float(i) + 0.5f) / n, (float(j) + 0.5f) / n};
      const EnvironmentSample s = env.sample(up, u);
      const double xi = s.radianceOverPdf.r * std::max(0.0f, dot(up, s.wi));
      sumI += xi, sumI2 += xi * xi;
      const double z = 1 - 2 * u.y, r = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3f d{float(r * std::cos(2 * kPi * u.x)), float(z),
                    float(r * std::sin(2 * kPi * u.x))};
      const double xu = 4 * kPi * env.radiance(d).r * std::max(0.0f, dot(up, d));
      sumU += xu, sumU2 += xu * xu;
    }
  const double m = double(n) * n;
  const double meanI = sumI / m, varI = sumI2 / m - meanI * meanI;
  const double meanU = sumU / m, varU = sumU2 / m - meanU * meanU;
  // Both estimate the same E ≈ 38 (the uniform one within its noise: the sun's 9 or so hits
  // out of 4096 are stratified, but each is worth ~1/9 of the total).
  EXPECT_NEAR(meanI, 38, 4);
  EXPECT_NEAR(meanU, meanI, 0.35 * meanI);
  EXPECT_LT(varI, varU / 100) << "importance " << varI << " uniform " << varU;
}

TEST(Environment, UniformSkyIsDrawnByCosineSoDiffuseReadsPiL) {
  // Cosine-weighted about n: L/pdf · cos θ = π·L for every sample, whatever n and u.
  const EnvironmentLight env(Rgb{0.2f, 0.5f, 1}, 1);
  for (const Vec3f n : {Vec3f{0, 1, 0}, normalize(Vec3f{1, -2, 0.5f})})
    for (int k = 0; k < 16; ++k) {
      const Vec2f u{(float(k % 4) + 0.3f) / 4, (float(k / 4) + 0.8f) / 4};
      const LightSample s = sampleLight(Light{env}, {1, 2, 3}, n, u);
      EXPECT_TRUE(s.atInfinity);
      const float cosTheta = dot(n, s.wi);
      ASSERT_GT(cosTheta, 0);
      EXPECT_NEAR(s.intensity.g * cosTheta, kPi * 0.5f, 1e-5);
      EXPECT_NEAR(env.pdf(n, s.wi), cosTheta / kPi, 1e-6);
    }
  EXPECT_EQ(env.radiance({0, -1, 0}), (Rgb{0.2f, 0.5f, 1}));
  EXPECT_EQ(lightSampleCount(Light{EnvironmentLight(Rgb{1, 1, 1}, 7)}), 7);
  EXPECT_FALSE(isDeltaLight(Light{env}));
}

TEST(Environment, BlackImageDrawsNothing) {
  const EnvironmentLight env(image(4, 2, [](int, int) { return Rgb{}; }), 1, 0, 1);
  EXPECT_TRUE(env.sample({0, 1, 0}, {0.3f, 0.6f}).radianceOverPdf.isBlack());
  EXPECT_EQ(env.pdf({0, 1, 0}, {0, 1, 0}), 0);
}

}  // namespace
}  // namespace glint
