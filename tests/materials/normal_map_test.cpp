// Normal and bump maps (materials/normal_map.h): the bent normal, its frame, and the bump
// shadowing term.
#include "materials/normal_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// An image whose data is one colour everywhere, or (ramp) whose first channel is its s
// coordinate; it has no colour conversion to get wrong, so these tests pin the geometry alone.
class FakeImage final : public ImageTexture {
 public:
  explicit FakeImage(Rgb data, bool ramp = false) : data_(data), ramp_(ramp) {}
  Rgb color(const ImageFootprint&) const override { return {}; }
  Rgb data(const ImageFootprint& at) const override {
    return ramp_ ? Rgb{at.st.x, at.st.x, at.st.x} : data_;
  }
  float coverage(const ImageFootprint&, bool) const override { return 1; }
  const std::string& path() const override { return path_; }

 private:
  Rgb data_;
  bool ramp_;
  std::string path_ = "fake";
};

// A point in the middle of a 2 × 2 square in the xy plane facing +z, u along +x, v along +y.
ShadingPoint squarePoint() {
  ShadingPoint sp;
  sp.ng = sp.ns = {0, 0, 1};
  sp.uv = {0.5f, 0.5f};
  sp.dpdu = sp.tangent = {2, 0, 0};
  sp.dpdv = {0, 2, 0};
  sp.tangentSign = 1;
  return sp;
}

const float kCos30 = std::sqrt(3.0f) / 2;

// The texel that encodes tangent-space normal m: (m + 1) / 2.
Rgb encoded(const Vec3f& m) { return {(m.x + 1) / 2, (m.y + 1) / 2, (m.z + 1) / 2}; }

TEST(NormalMap, ATexelTiltedTowardsPlusUBendsTheNormalTowardsTheTangent) {
  ShadingMaps maps;
  maps.normal.image = std::make_shared<FakeImage>(encoded({0.5f, 0, kCos30}));
  const Vec3f n = mappedNormal(maps, squarePoint(), {0, 0, 1}, 0.01f);
  // m = (sin 30°, 0, cos 30°) in the frame (T = +x, B = +y, N = +z); float rounding: 1e-6.
  EXPECT_NEAR(n.x, 0.5, 1e-6);
  EXPECT_NEAR(n.y, 0, 1e-6);
  EXPECT_NEAR(n.z, kCos30, 1e-6);
}

TEST(NormalMap, TheBitangentSignTurnsGreenTowardsPlusV) {
  // m = (0, sin 30°, cos 30°): +v is +y with sign +1; a mirrored mapping (sign −1, v along −y)
  // turns the same texel towards −y.
  ShadingMaps maps;
  maps.normal.image = std::make_shared<FakeImage>(encoded({0, 0.5f, kCos30}));
  ShadingPoint sp = squarePoint();
  EXPECT_NEAR(mappedNormal(maps, sp, {0, 0, 1}, 0.01f).y, 0.5, 1e-6);
  sp.tangentSign = -1;
  EXPECT_NEAR(mappedNormal(maps, sp, {0, 0, 1}, 0.01f).y, -0.5, 1e-6);
}

TEST(NormalMap, ScaleMultipliesXAndYBeforeNormalising) {
  // glTF: normalize((2c − 1) · (scale, scale, 1)). m = (0.5, 0, cos 30°) at scale 2 is
  // (1, 0, cos 30°) / |·|: x = 1 / sqrt(1 + 3/4).
  ShadingMaps maps;
  maps.normal.image = std::make_shared<FakeImage>(encoded({0.5f, 0, kCos30}));
  maps.normal.scale = 2;
  const Vec3f n = mappedNormal(maps, squarePoint(), {0, 0, 1}, 0.01f);
  EXPECT_NEAR(n.x, 1 / std::sqrt(1.75), 1e-6);
  EXPECT_NEAR(n.z, kCos30 / std::sqrt(1.75), 1e-6);
}

TEST(NormalMap, TheMappedNormalStaysOnTheGeometricSide) {
  // A texel pointing below the surface (m = (1, 0, −1)/√2) is turned up towards ng, keeping
  // its direction across the surface (+x), to a cosine of 1/64 with ng. Float rounding: 1e-6.
  ShadingMaps maps;
  maps.normal.image = std::make_shared<FakeImage>(encoded({0.7071f, 0, -0.7071f}));
  const Vec3f n = mappedNormal(maps, squarePoint(), {0, 0, 1}, 0.01f);
  EXPECT_NEAR(n.z, 1.0 / 64, 1e-6);
  EXPECT_NEAR(n.x, std::sqrt(1 - 1.0 / 4096), 1e-6);
  EXPECT_NEAR(n.y, 0, 1e-6);
}

TEST(BumpMap, ALinearRampTiltsTheNormalByItsSlope) {
  // h = scale · s with s = u: ∂h/∂u = scale, and |dp/du| = 2, so the normal leans back from +u
  // by atan(scale / 2): scale = 2 tan 30° gives (−sin 30°, 0, cos 30°). The central difference
  // of a linear ramp is exact up to float rounding of the lookups (1e-5).
  ShadingMaps maps;
  maps.bump.image = std::make_shared<FakeImage>(Rgb{}, true);
  maps.bump.scale = 2 * std::tan(kPi / 6);
  const Vec3f n = mappedNormal(maps, squarePoint(), {0, 0, 1}, 0.01f);
  EXPECT_NEAR(n.x, -0.5, 1e-5);
  EXPECT_NEAR(n.y, 0, 1e-6);
  EXPECT_NEAR(n.z, kCos30, 1e-5);
}

TEST(BumpMap, TheTextureTransformCarriesTheSlopeToUv) {
  // uv_scale 2: s = 2u, so ∂h/∂u doubles and the lean is atan(2 · scale / 2).
  ShadingMaps maps;
  maps.bump.image = std::make_shared<FakeImage>(Rgb{}, true);
  maps.bump.scale = std::tan(kPi / 6);
  maps.bump.uvTransform = UvTransform::offsetRotateScale({0, 0}, 0, {2, 1});
  const Vec3f n = mappedNormal(maps, squarePoint(), {0, 0, 1}, 0.01f);
  EXPECT_NEAR(n.x, -0.5, 1e-5);
  EXPECT_NEAR(n.z, kCos30, 1e-5);
}

TEST(BumpShadowing, IsOneWhereTheLightLiesAlongTheBentNormal) {
  // Normal bent 30° towards +x, light 30° off the vertical towards +x (the end-to-end test's
  // set-up): g = cos 30° / (1 · cos 30°) = 1.
  const Vec3f unmapped{0, 0, 1}, mapped{0.5f, 0, kCos30};
  EXPECT_NEAR(bumpShadowing(unmapped, mapped, mapped), 1, 1e-6);
  // Light straight above: g = 1 / cos² 30° > 1, clamped to 1.
  EXPECT_EQ(bumpShadowing(unmapped, mapped, unmapped), 1);
}

TEST(BumpShadowing, FadesAsTheCubicOfChiangEtAl) {
  // Light 70° off the vertical towards +x: g = cos 70° / (cos 40° · cos 30°), and the factor
  // is −g³ + g² + g.
  const Vec3f unmapped{0, 0, 1}, mapped{0.5f, 0, kCos30};
  const float a = 70 * kPi / 180;
  const Vec3f wi{std::sin(a), 0, std::cos(a)};
  const double g = std::cos(70 * M_PI / 180) / (std::cos(40 * M_PI / 180) * std::cos(M_PI / 6));
  EXPECT_NEAR(bumpShadowing(unmapped, mapped, wi), -g * g * g + g * g + g, 1e-5);
  // Light below the unmapped surface, though the bent normal faces it: g < 0, nothing.
  const float below = 95 * kPi / 180;
  EXPECT_EQ(bumpShadowing(unmapped, mapped, {std::sin(below), 0, std::cos(below)}), 0);
}

}  // namespace
}  // namespace glint
