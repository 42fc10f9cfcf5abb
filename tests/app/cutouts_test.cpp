// Opacity cut-outs end to end (materials/cutout.h): a scene's "opacity", MTL map_d and glTF
// alphaMode MASK cut holes that camera rays and shadow rays pass through, in the production
// kernel and in the reference integrator alike.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "accel/accelerator.h"
#include "film/oiio_module.h"
#include "gltf_util.h"
#include "oracle_util.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

RenderOptions quiet() {
  RenderOptions opt;
  opt.progress = false;
  return opt;
}

Scene sceneAt(const std::string& text, const std::string& name) {
  const std::string path = test::writeTemp(name, text);
  return loadSceneText(text, path, test::tempDir().string());
}

// Pixel (x, y)'s red channel.
double red(const Film& film, int x, int y) { return film.pixel(x, y)[0]; }

// A 16 × 4 orthographic view of the unit square x, y ∈ [0, 1] at z = 0 from +z (each column c
// at x = (c + 0.5)/16, u = x for a quad or mesh on it), lit head on by a unit directional light,
// with a background of red 0.2: a surface with k_d 1 reads 1, a hole 0.2. Columns 2–5 lie at
// u ∈ [0.16, 0.34], inside the half matte's holes; columns 10–13 at u ∈ [0.66, 0.84], solid (a
// texel and more from both edges, where filtering blends black and white).
std::string squareView(const std::string& objects, const std::string& materials = "{}") {
  return R"({"render": {"width": 16, "height": 4, "spp": 1, "sampler": "regular",
                        "background": [0.2, 0.4, 0.6]},
    "camera": {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0],
               "height": 0.25},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": [1, 1, 1]}],
    "materials": )" +
         materials + R"(, "objects": [)" + objects + "]}";
}

void expectHolesLeftSolidRight(const Film& film, double solid, const std::string& what) {
  for (int y = 0; y < 4; ++y) {
    for (int x = 2; x <= 5; ++x) EXPECT_EQ(red(film, x, y), 0.2f) << what << " hole " << x;
    for (int x = 10; x <= 13; ++x) EXPECT_NEAR(red(film, x, y), solid, 1e-5) << what << " " << x;
  }
}

TEST(Cutouts, ShadowsFallThroughTheHoles) {
  // A cut quad at height 1 over x ∈ [0, 1] (u = x), lit by a unit directional light along
  // (1, −1, 0): its shadow falls on the floor at x ∈ [1, 2], the point under u at x = 1 + u.
  // Seen from above: floor lit through a hole reads k_d·I·cos 45° = 0.5·0.70711 = 0.35355; in
  // the shadow of the solid half, 0 (no ambient). Columns c at x = 1 + (c + 0.5)/16 as above.
  const Scene scene =
      sceneAt(R"({"render": {"width": 16, "height": 4, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [1.5, 5, 0], "look_at": [1.5, 0, 0],
               "up": [0, 0, -1], "height": 0.25},
    "materials": {"floor": {"type": "phong", "kd": [0.5, 0.5, 0.5]},
                  "cut": {"type": "phong", "opacity": {"image": ")" +
                  test::writeHalfMatte() + R"("}}},
    "lights": [{"type": "directional", "direction": [1, -1, 0], "intensity": [1, 1, 1]}],
    "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
                {"type": "quad", "corner": [0, 1, -1], "edge1": [1, 0, 0], "edge2": [0, 0, 2],
                 "material": "cut"}]})",
              "cut_shadow.json");
  for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto accel = makeAccelerator(kind, scene);
    const RenderResult result = renderScene(scene, *accel, quiet());
    const Film& film = result.film;
    for (int y = 0; y < 4; ++y) {
      for (int x = 2; x <= 5; ++x)
        EXPECT_NEAR(red(film, x, y), 0.5 * std::sqrt(0.5), 1e-6) << accel->name() << " lit " << x;
      for (int x = 10; x <= 13; ++x) EXPECT_EQ(red(film, x, y), 0) << accel->name() << " " << x;
    }
    EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, quiet(), result, "cut shadow"), 0);
  }
}

TEST(Cutouts, MtlMapDCutsWhereItsGreyIsDark) {
  test::writeHalfMatte();  // beside the OBJ, as map_d names it
  test::writeTemp("cut_quad.mtl",
                  "newmtl cut\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\n"
                  "map_d half_matte.png\n");
  test::writeTemp("cut_quad.obj",
                  "mtllib cut_quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl cut\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  const Scene scene =
      sceneAt(squareView(R"({"type": "mesh", "file": "cut_quad.obj"})"), "mtl.json");
  ASSERT_TRUE(scene.features.cutouts);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  // Kd 1 under the unit light along the normal: 1.
  expectHolesLeftSolidRight(renderScene(scene, *accel, quiet()).film, 1.0, "map_d");
}

TEST(Cutouts, GltfMaskCutsWhereBaseColourAlphaIsBelowTheCutoff) {
  // 8 × 8 white RGBA, alpha 0.3 in the left half and 1 in the right (16-bit codes).
  std::vector<uint16_t> codes;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      codes.insert(codes.end(), {65535, 65535, 65535, uint16_t(x < 4 ? 19661 : 65535)});
  const std::string png = (test::tempDir() / "alpha_half.png").string();
  oiio_module::writeImage(png, png, 8, 8, 4, 16, codes);
  const auto render = [](const std::string& material, const std::string& name) {
    test::writeTemp(name + ".gltf", test::gltfSquares({0}, "[" + material + "]", "alpha_half.png"));
    const Scene scene =
        sceneAt(squareView(R"({"type": "mesh", "file": ")" + name + R"(.gltf"})"), name + ".json");
    const auto accel = makeAccelerator(AccelKind::Embree, scene);
    return renderScene(scene, *accel, quiet()).film;
  };
  const std::string textured =
      R"("pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0})";
  // White, not metallic, roughness 1 (Blinn-Phong exponent 1): k_d 1 and k_s 0.04 head on, 1.04.
  expectHolesLeftSolidRight(render(R"({"alphaMode": "MASK", )" + textured + "}", "mask"), 1.04,
                            "MASK at the default cutoff 0.5");
  // Alpha 0.3 is kept at a cutoff of 0.25: no hole anywhere.
  const Film low = render(R"({"alphaMode": "MASK", "alphaCutoff": 0.25, )" + textured + "}", "low");
  for (int x = 0; x < 16; ++x) EXPECT_NEAR(red(low, x, 1), 1.04, 1e-5) << x;
  // MASK with a base colour alpha of 0.4 and no texture: the whole square is a hole.
  const Film gone = render(
      R"({"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.4]}})",
      "gone");
  for (int x = 0; x < 16; ++x) EXPECT_EQ(red(gone, x, 1), 0.2f) << x;
  // OPAQUE (the default) ignores alpha.
  const Film opaque = render("{" + textured + "}", "opaque");
  for (int x = 0; x < 16; ++x) EXPECT_NEAR(red(opaque, x, 1), 1.04, 1e-5) << x;
  // A mode glTF does not define is opaque too, and said to be (it was without a word).
  testing::internal::CaptureStderr();
  const Film unknown = render(R"({"alphaMode": "MASKX", )" + textured + "}", "unknown");
  const std::string warnings = testing::internal::GetCapturedStderr();
  for (int x = 0; x < 16; ++x) EXPECT_NEAR(red(unknown, x, 1), 1.04, 1e-5) << x;
  EXPECT_NE(warnings.find(R"(alphaMode "MASKX" is not one glTF defines (OPAQUE, MASK, BLEND): )"
                          "opaque"),
            std::string::npos)
      << warnings;
}

TEST(Cutouts, ARealGltfWithAlphaModeBlendIsRenderedOpaqueWithAWarning) {
  const std::string file = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "assimp-testmodels is not installed (tools/lib.sh installs it)";
  const auto r = test::runGlint("render " + file + " --spp 1 --width 32 --height 24 -o " +
                                (test::tempDir() / "clearcoat.exr").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("Partial_Coating: alphaMode BLEND is not rendered"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace glint
