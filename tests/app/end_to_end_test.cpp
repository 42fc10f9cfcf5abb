// Tiny scenes whose every pixel is known, through the whole program and the EXR round trip.
#include <gtest/gtest.h>

#include "film/exr_output.h"
#include "test_util.h"

namespace glint {
namespace {

Image renderToImage(const std::string& name, const std::string& sceneText,
                    const std::string& extraArgs = "") {
  const std::string scene = test::writeTemp(name + ".json", sceneText);
  const std::string exr = (test::tempDir() / (name + ".exr")).string();
  const auto r = test::runGlint("render " + scene + " -o " + exr + " --quiet " + extraArgs);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return readImage(exr);
}

const float* px(const Image& img, int x, int y) {
  return &img.pixels[(size_t(y) * size_t(img.width) + size_t(x)) * size_t(img.channels)];
}

TEST(EndToEnd, EmptySceneIsOpaqueBackgroundOrTransparentFilm) {
  // The beauty is premultiplied (docs/output.md, Alpha): by default the background is opaque,
  // RGB = background with alpha 1; on a transparent film a miss leaves RGB 0 with alpha 0
  // (RGB = background with alpha 0 would composite as an additive glow).
  const std::string text = R"({
    "render": {"width": 5, "height": 3, "spp": 2, "background": [0.1, 0.2, 0.3]},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "objects": []})";
  const Image opaque = renderToImage("empty", text);
  const Image transparent = renderToImage("empty_transparent", text, "--transparent-background");
  for (const Image* img : {&opaque, &transparent}) {
    ASSERT_EQ(img->width, 5);
    ASSERT_EQ(img->height, 3);
    ASSERT_EQ(img->channels, 4);  // RGBA float
  }
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(px(opaque, x, y)[0], 0.1f);
      EXPECT_EQ(px(opaque, x, y)[1], 0.2f);
      EXPECT_EQ(px(opaque, x, y)[2], 0.3f);
      EXPECT_EQ(px(opaque, x, y)[3], 1.0f);
      for (int c = 0; c < 4; ++c) EXPECT_EQ(px(transparent, x, y)[c], 0.0f);
    }
}

TEST(EndToEnd, SphereMaskUnderOrthographicCamera) {
  // 8×8 pixels over a 4×4 view: pixel centres at ±0.25, ±0.75, ±1.25, ±1.75. A centre lies on
  // the unit sphere's disk iff u² + v² < 1 (no centre is on the circle). The sphere shows only
  // ambient: k_a·I_a = (0.25, 0.5, 0.75) exactly; misses show the background (opaque). The
  // transparent film's alpha is the mask.
  const std::string text = R"({
    "render": {"width": 8, "height": 8, "spp": 1, "sampler": "regular",
               "background": [0.1, 0.2, 0.3], "ambient": [0.25, 0.5, 0.75]},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 4},
    "materials": {"m": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})";
  const Image img = renderToImage("mask", text);
  const Image film = renderToImage("mask_transparent", text, "--transparent-background");
  int covered = 0;  // pixels the transparent film shows the sphere in
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const float u = -1.75f + 0.5f * float(x), v = 1.75f - 0.5f * float(y);
      const bool in = u * u + v * v < 1;
      const float* p = px(img, x, y);
      EXPECT_EQ(p[3], 1.0f) << x << "," << y;
      EXPECT_EQ(p[0], in ? 0.25f : 0.1f) << x << "," << y;
      EXPECT_EQ(p[2], in ? 0.75f : 0.3f) << x << "," << y;
      const float* t = px(film, x, y);
      covered += t[3] == 1.0f;
      EXPECT_EQ(t[3], in ? 1.0f : 0.0f) << x << "," << y;
      EXPECT_EQ(t[0], in ? 0.25f : 0.0f) << x << "," << y;
    }
  EXPECT_EQ(covered, 12);  // centres (±0.25,±0.25), (±0.25,±0.75), (±0.75,±0.25)
}

TEST(EndToEnd, LambertPlaneUnderDirectionalLight) {
  // n = +y, light travelling along (0,−1,−1)/√2: cosθ = 1/√2, so L = k_d·I·cosθ
  // = 0.5 · 1 · 0.70710678 = 0.35355339 at every pixel (no ambient, nothing in shadow).
  const Image img = renderToImage("lambert", R"({
    "render": {"width": 6, "height": 4, "spp": 4},
    "camera": {"type": "orthographic", "eye": [0,5,0], "look_at": [0,0,0], "up": [0,0,-1], "height": 2},
    "materials": {"m": {"type": "phong", "kd": [0.5,0.5,0.5], "ka": [0,0,0]}},
    "lights": [{"type": "directional", "direction": [0,-1,-1], "intensity": [1,1,1]}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}]})");
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      EXPECT_NEAR(px(img, x, y)[0], 0.35355339f, 1e-6) << x << "," << y;
      EXPECT_EQ(px(img, x, y)[3], 1.0f);
    }
}

TEST(EndToEnd, PointLightShadowAndInverseSquare) {
  // A point light 2 above the plane: straight below it L = k_d·I/r² = 0.8·4/4 = 0.8. A quad at
  // y = 1 hides the light from the pixel below it: only ambient is left, k_a·I_a = 0.
  const std::string base = R"({
    "render": {"width": 3, "height": 1, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [0,5,0], "look_at": [0,0,0], "up": [0,0,-1], "height": 1},
    "materials": {"m": {"type": "phong", "kd": [0.8,0.8,0.8], "ka": [0,0,0]}},
    "lights": [{"type": "point", "position": [0,2,0], "intensity": [4,4,4], "falloff": "inverse_square"}],
    "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"})";
  // The view is 3 × 1 units; pixel centres sit at x = −1, 0, 1 on the plane (u = +x here).
  const Image lit = renderToImage("lit", base + "]}");
  EXPECT_NEAR(px(lit, 1, 0)[0], 0.8f, 1e-6);
  // The left centre's segment to the light (0,2,0) crosses y = 1 at x = −0.5: a small quad there
  // occludes it without being seen by the camera rays through x = −1, 0, 1.
  const Image shadowed = renderToImage(
      "shadowed", base + R"(, {"type": "quad", "corner": [-0.55,1,-0.05], "edge1": [0.1,0,0],
      "edge2": [0,0,0.1], "material": "m"}]})");
  EXPECT_EQ(px(shadowed, 0, 0)[0], 0.0f);
  EXPECT_EQ(px(shadowed, 1, 0)[0], px(lit, 1, 0)[0]);
  // The right centre is untouched: r² = 1 + 4 = 5, cosθ = 2/√5, L = 0.8·4·cosθ/r².
  EXPECT_NEAR(px(shadowed, 2, 0)[0], 0.8f * 4 * (2 / std::sqrt(5.0f)) / 5, 1e-6);
}

}  // namespace
}  // namespace glint
