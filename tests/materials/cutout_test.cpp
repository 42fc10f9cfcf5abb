// Opacity cut-outs (materials/cutout.h): where a coverage falls below the cutoff.
#include "materials/cutout.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// An image whose coverage is its s coordinate (a ramp across it), remembering what it was asked.
class RampImage final : public ImageTexture {
 public:
  Rgb color(const ImageFootprint&) const override { return {}; }
  Rgb data(const ImageFootprint&) const override { return {}; }
  float coverage(const ImageFootprint& at, bool greyWithoutAlpha) const override {
    lastSt = at.st;
    lastGrey = greyWithoutAlpha;
    return at.st.x;
  }
  const std::string& path() const override { return path_; }
  mutable Vec2f lastSt;
  mutable bool lastGrey = false;

 private:
  std::string path_ = "ramp";
};

TEST(Cutout, AConstantCoverageCutsEverythingOrNothing) {
  Cutout c;
  EXPECT_FALSE(c.active());  // coverage 1 ≥ cutoff 0.5: solid everywhere
  EXPECT_FALSE(c.holeAt({0.3f, 0.7f}));
  c.coverage = 0.4f;  // below the cutoff: the whole surface is a hole
  EXPECT_TRUE(c.active());
  EXPECT_TRUE(c.holeAt({0.3f, 0.7f}));
  c.cutoff = 0.4f;  // equal to the cutoff is kept (glTF: alpha < alphaCutoff is cut)
  EXPECT_FALSE(c.active());
  EXPECT_FALSE(c.holeAt({0.3f, 0.7f}));
}

TEST(Cutout, AnImageCutsWhereItsCoverageTimesTheConstantIsBelowTheCutoff) {
  auto ramp = std::make_shared<RampImage>();
  Cutout c;
  c.image = ramp;
  c.coverage = 0.8f;
  ASSERT_TRUE(c.active());
  // coverage 0.8·s against 0.5: holes for s < 0.625.
  EXPECT_TRUE(c.holeAt({0.6f, 0.2f}));
  EXPECT_FALSE(c.holeAt({0.65f, 0.2f}));
  // (u, v) has its origin at the bottom left, images at the top: t = 1 − v.
  EXPECT_FLOAT_EQ(ramp->lastSt.x, 0.65f);
  EXPECT_FLOAT_EQ(ramp->lastSt.y, 0.8f);
  EXPECT_TRUE(ramp->lastGrey);  // the default channel: alpha, else a grey matte
  c.channel = Cutout::Channel::Alpha;
  c.holeAt({0.65f, 0.2f});
  EXPECT_FALSE(ramp->lastGrey);
}

TEST(Cutout, TheImageIsReadThroughItsUvTransform) {
  auto ramp = std::make_shared<RampImage>();
  Cutout c;
  c.image = ramp;
  // Scaled by 2 and offset by 0.1 in u: u = 0.2 reads s = 0.5, kept at the cutoff 0.5.
  c.uvTransform = UvTransform::offsetRotateScale({0.1f, 0}, 0, {2, 1});
  EXPECT_FALSE(c.holeAt({0.2f, 0.5f}));
  EXPECT_FLOAT_EQ(ramp->lastSt.x, 0.5f);
  EXPECT_TRUE(c.holeAt({0.19f, 0.5f}));  // s = 0.48
}

}  // namespace
}  // namespace glint
