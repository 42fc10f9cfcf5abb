// Image textures end to end (issue 23): texture coordinates and maps from real files, read by
// OpenImageIO into a MIP pyramid and linearised by OCIO, filtered over the pixel's footprint
// through mirrors as directly.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>

#include "accel/accelerator.h"
#include "film/image_file.h"
#include "io/mesh_io.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// sRGB's decoding (IEC 61966-2-1), the reference OCIO's built-in curve must match.
double srgbToLinear(int code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Film render(const std::string& sceneText, const std::string& name) {
  const std::string path = test::writeTemp(name, sceneText);
  const Scene scene = loadSceneText(sceneText, path, test::tempDir().string());
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(scene, *accel, opt).film;
}

// An 8 × 8 texture of four 4 × 4 quadrants, top left, top right, bottom left, bottom right.
constexpr int kQuadrant[4][3] = {{50, 128, 200}, {255, 0, 30}, {10, 90, 160}, {128, 128, 128}};

void writeQuadrantTexture(const std::string& path) {
  std::vector<uint16_t> codes;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) codes.push_back(uint16_t(kQuadrant[(y / 4) * 2 + x / 4][c]));
  writeRgbImage(path, 8, 8, 8, codes);
}

TEST(Textures, MapKdOnUvsReproducesTheTexturesLinearisedTexels) {
  writeQuadrantTexture((test::tempDir() / "quadrants.png").string());
  // A unit quad whose (u, v) runs with x and y, its MTL's map_Kd the texture.
  test::writeTemp("textured_quad.mtl",
                  "newmtl tex\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd quadrants.png\n");
  test::writeTemp("textured_quad.obj",
                  "mtllib textured_quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl tex\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  // Orthographic, the quad filling the 16 × 16 frame; one sample at each pixel's centre; a
  // unit light along the normal, so that each pixel is k_d · 1 · cos 0 = k_d.
  const Film film = render(R"({
    "render": {"width": 16, "height": 16, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0],
               "height": 1},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": [1, 1, 1]}],
    "objects": [{"type": "mesh", "file": "textured_quad.obj"}]})",
                           "textured_quad.json");
  // Each quadrant's middle pixel: a pixel is half a texel, so the filter reads texels of the
  // quadrant only (bilinear, magnified: the texels 1 and 2 on each axis around 1.75 texel
  // centres into quadrant 0, and likewise in the others, are all inside it), and gives
  // the texel's linearised value up to float rounding of the filter weights (1e-5).
  const int middles[4][2] = {{4, 4}, {11, 4}, {4, 11}, {11, 11}};
  for (int q = 0; q < 4; ++q) {
    const float* px = film.pixel(middles[q][0], middles[q][1]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(px[c], srgbToLinear(kQuadrant[q][c]), 1e-5)
          << "quadrant " << q << " channel " << c;
  }
}

TEST(Textures, AMeshFilesTextureBytesJoinTheSceneHash) {
  // merge refuses crops of different scenes by this hash: a changed map_Kd must change it, as a
  // changed mesh or JSON image texture does.
  const std::string png = (test::tempDir() / "hashed.png").string();
  writeQuadrantTexture(png);
  test::writeTemp("hashed_quad.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd hashed.png\n");
  test::writeTemp("hashed_quad.obj",
                  "mtllib hashed_quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                  "vt 0 0\nvt 1 0\nvt 0 1\nusemtl tex\nf 1/1 2/2 3/3\n");
  const std::string text = R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "objects": [{"type": "mesh", "file": "hashed_quad.obj"}]})";
  const auto hash = [&] {
    return loadSceneText(text, test::writeTemp("hashed.json", text), test::tempDir().string())
        .sourceHash;
  };
  const uint64_t before = hash();
  EXPECT_EQ(hash(), before);  // the same bytes, the same hash
  // Another image in its place (written beside it, then copied over: Glint refuses to write
  // over an input of the run).
  const std::string other = (test::tempDir() / "hashed_other.png").string();
  writeRgbImage(other, 1, 1, 8, {1, 2, 3});
  test::writeTemp("hashed.png", test::readFile(other));
  EXPECT_NE(hash(), before);
}

TEST(Textures, VertexColoursMultiplyTheDiffuseColour) {
  // OBJ's extension "v x y z r g b": the bottom corners red-ish, the top ones blue-ish; Kd 0.5.
  test::writeTemp("coloured_quad.mtl", "newmtl c\nKa 0 0 0\nKd 0.5 0.5 0.5\nKs 0 0 0\nillum 1\n");
  test::writeTemp("coloured_quad.obj",
                  "mtllib coloured_quad.mtl\nv 0 0 0 0.8 0.2 0.1\nv 1 0 0 0.8 0.2 0.1\n"
                  "v 1 1 0 0.1 0.3 0.9\nv 0 1 0 0.1 0.3 0.9\nusemtl c\nf 1 2 3\nf 1 3 4\n");
  const Film film = render(R"({
    "render": {"width": 16, "height": 16, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0],
               "height": 1},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": [1, 1, 1]}],
    "objects": [{"type": "mesh", "file": "coloured_quad.obj"}]})",
                           "coloured_quad.json");
  // Lit head on by a unit light, a pixel is k_d = 0.5 × the colour interpolated at its centre:
  // linear in y from the bottom colour (y = 0) to the top (y = 1). Row 3 from the top has its
  // centre at y = 1 − 3.5/16. Float interpolation: 1e-6.
  const double y = 1 - 3.5 / 16;
  const double expected[3] = {0.5 * (0.8 + (0.1 - 0.8) * y), 0.5 * (0.2 + (0.3 - 0.2) * y),
                              0.5 * (0.1 + (0.9 - 0.1) * y)};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(film.pixel(8, 3)[c], expected[c], 1e-6) << c;
}

TEST(Textures, AJsonImageTextureSaysWhichFileIsMissing) {
  const std::string error = test::sceneErrorOf(R"({
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "phong", "kd": {"image": "no_such_texture.png"}}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  EXPECT_NE(error.find("scene.json:3"), std::string::npos) << error;
  EXPECT_NE(error.find("materials.m.kd.image"), std::string::npos) << error;
  EXPECT_NE(error.find("no_such_texture.png"), std::string::npos) << error;
}

TEST(Textures, ACorruptTextureIsRefusedWhenTheSceneLoads) {
  // A PNG signature and a header chunk, then nothing: OpenImageIO cannot read its texels.
  writeQuadrantTexture((test::tempDir() / "whole.png").string());
  const std::string whole = test::readFile((test::tempDir() / "whole.png").string());
  test::writeTemp("truncated.png", whole.substr(0, 40));
  const std::string error = test::sceneErrorOf(R"({
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "phong", "kd": {"image": ")" +
                                               (test::tempDir() / "truncated.png").string() +
                                               R"("}}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  EXPECT_NE(error.find("truncated.png"), std::string::npos) << error;
  EXPECT_NE(error.find("cannot read texture"), std::string::npos) << error;
}

TEST(Textures, ATruncatedTiffIsRefusedNotRenderedBlack) {
  // A 256² uncompressed TIFF cut at half its bytes: its header and first strips read, its last
  // strips are missing. OpenImageIO's TIFF reader reports them as errors yet says it succeeded,
  // and the texture rendered black there, exit 0. Whole, the same file loads.
  const std::string whole = (test::tempDir() / "whole.tif").string();
  {
    OIIO::ImageSpec spec(256, 256, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("compression", "none");
    std::vector<unsigned char> texels(256 * 256 * 3);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<unsigned char>(i * 7);
    auto out = OIIO::ImageOutput::create(whole);
    ASSERT_TRUE(out && out->open(whole, spec) &&
                out->write_image(OIIO::TypeDesc::UINT8, texels.data()) && out->close());
  }
  const std::string bytes = test::readFile(whole);
  const std::string cut = test::writeTemp("truncated.tif", bytes.substr(0, bytes.size() / 2));
  const auto scene = [](const std::string& texture) {
    return R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "phong", "kd": {"image": ")" +
           texture + R"("}}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
  };
  EXPECT_NO_THROW(test::sceneFromText(scene(whole)));
  const std::string error = test::sceneErrorOf(scene(cut));
  EXPECT_EQ(error.rfind("scene.json:2: materials.m.kd.image: cannot read texture " + cut + ": ", 0),
            0u)
      << error;
}

// Vertical stripes 4 texels wide on a 256² texture, emitted (k_e) by a 2 × 2 quad: a pixel's
// colour is the texture filtered over its footprint, and nothing else.
std::string stripesScene(const std::string& quad, const std::string& extra) {
  return R"({
    "render": {"width": 48, "height": 48, "spp": 1, "sampler": "regular"},
    "camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "vfov": 10},
    "materials": {
      "stripes": {"type": "phong", "kd": [0, 0, 0], "ke": {"image": "stripes.png"}},
      "mirror": {"type": "mirror", "km": [1, 1, 1]}},
    "objects": [)" +
         quad + extra + "]}";
}

TEST(Textures, ATextureSeenInAFlatMirrorIsFilteredAsSeenDirectly) {
  std::vector<uint16_t> codes;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 3; ++c) codes.push_back((x / 4) % 2 ? 255 : 0);
  writeRgbImage((test::tempDir() / "stripes.png").string(), 256, 256, 8, codes);
  // Directly: the quad 10 units away. Through a mirror in the plane x + z = −5 (turning the
  // view towards +x): the quad 5 units beyond it, placed where the mirror images it onto the
  // direct quad, corner to corner, so each pixel sees the same (u, v) over the same distance.
  const Film direct = render(stripesScene(R"({"type": "quad", "corner": [-1, -1, -10],
      "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "stripes"})",
                                          ""),
                             "stripes_direct.json");
  const Film mirrored = render(stripesScene(R"({"type": "quad", "corner": [5, -1, -4],
      "edge1": [0, 0, -2], "edge2": [0, 2, 0], "material": "stripes"})",
                                            R"(, {"type": "quad", "corner": [-2, -2, -3],
      "edge1": [4, 0, -4], "edge2": [0, 4, 0], "material": "mirror"})"),
                               "stripes_mirrored.json");
  // A pixel covers 3.4 texels of the stripes at 10 units: filtered, they neither vanish into
  // grey nor alias at full contrast. Were the mirror ray's cone started afresh at the mirror,
  // its footprint would be half as wide and the stripes clearly sharper (tested below).
  double maxDifference = 0, contrast = 0;
  for (int y = 8; y < 40; ++y)
    for (int x = 8; x < 40; ++x) {
      maxDifference = std::max(maxDifference,
                               std::fabs(double(direct.pixel(x, y)[0]) - mirrored.pixel(x, y)[0]));
      contrast = std::max(contrast, std::fabs(direct.pixel(x, y)[0] - 0.5));
    }
  // The two agree to float rounding of the hit points (the mirrored point is found through a
  // reflection; 1e-3 allows positions ~1e-6 apart on stripes of slope ~1 per texel).
  EXPECT_LT(maxDifference, 1e-3);
  EXPECT_GT(contrast, 0.05);  // the comparison has something to compare
  // Four samples per pixel: each sample's footprint is half as wide (1/√spp), and the same
  // pixels' samples differ visibly from the one-sample footprint: the filter does respond to
  // the width the cone carries, by far more than the tolerance above.
  std::string sharper = stripesScene(R"({"type": "quad", "corner": [-1, -1, -10],
      "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "stripes"})",
                                     "");
  sharper.replace(sharper.find("\"spp\": 1"), 8, "\"spp\": 4");
  const Film fine = render(sharper, "stripes_fine.json");
  double fineContrast = 0;
  for (int y = 8; y < 40; ++y)
    for (int x = 8; x < 40; ++x) fineContrast += std::fabs(fine.pixel(x, y)[0] - 0.5);
  double directContrast = 0;
  for (int y = 8; y < 40; ++y)
    for (int x = 8; x < 40; ++x) directContrast += std::fabs(direct.pixel(x, y)[0] - 0.5);
  EXPECT_GT(std::fabs(fineContrast - directContrast) / (32 * 32), 10 * 1e-3);
}

TEST(Textures, RealAssetsKeepTheirTextureCoordinatesAndMaps) {
  const std::string box = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  const std::string spider = "/usr/share/assimp/models/OBJ/spider.obj";
  if (!std::filesystem::exists(box) || !std::filesystem::exists(spider))
    GTEST_SKIP() << "assimp-testmodels is not installed (tools/lib.sh installs it)";
  // Cesium's textured box: one material, its base colour from CesiumLogoFlat.png, 24 vertices
  // (4 per face) each with (u, v).
  const MeshFile b = loadMeshFile(box);
  ASSERT_EQ(b.parts.size(), 1u);
  EXPECT_EQ(b.parts[0].uvs.size(), b.parts[0].positions.size());
  EXPECT_EQ(b.materials[0].surface.kd.pattern, TexturePattern::Image);
  EXPECT_NE(b.materials[0].surface.kd.image->path().find("CesiumLogoFlat.png"), std::string::npos);
  // The spider: its MTL names a JPEG map per material with Windows separators
  // (".\\SpiderTex.jpg"); the four materials its faces use (Skin, HLeibTex, BeinTex,
  // Augentex) each find their own.
  const MeshFile s = loadMeshFile(spider);
  ASSERT_EQ(s.materials.size(), 4u);
  for (const Material& m : s.materials)
    EXPECT_EQ(m.surface.kd.pattern, TexturePattern::Image) << m.name;
  for (const TriangleMesh& part : s.parts) EXPECT_EQ(part.uvs.size(), part.positions.size());
}

TEST(Textures, AnImageEmbeddedInAGlbRendersAsTheSameImageBesideTheFile) {
  const std::string dir = "/usr/share/assimp/models/glTF2/";
  const std::string beside = dir + "BoxTextured-glTF/BoxTextured.gltf",
                    glb = dir + "BoxTextured-glTF-Binary/BoxTextured.glb",
                    dataUri = dir + "BoxTextured-glTF-Embedded/BoxTextured.gltf";
  if (!std::filesystem::exists(glb) || !std::filesystem::exists(dataUri))
    GTEST_SKIP() << "assimp-testmodels is not installed (tools/lib.sh installs it)";
  // The same box three ways: its PNG beside the file, in the GLB's binary chunk, and as a
  // base64 data URI. OpenImageIO reads the embedded bytes from memory (no file written); the
  // frames are the same bytes' texels, so equal exactly.
  const auto frame = [](const std::string& asset, const std::string& name) {
    const std::string out = (test::tempDir() / name).string();
    const auto r =
        test::runGlint("render " + asset + " --quiet --spp 2 --width 40 --height 30 -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("left out"), std::string::npos) << r.output;
    return out;
  };
  const std::string a = frame(beside, "box_beside.exr"), b = frame(glb, "box_glb.exr"),
                    c = frame(dataUri, "box_data_uri.exr");
  for (const std::string& other : {b, c}) {
    const auto r = test::runGlint("compare " + a + " " + other + " --json -");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("\"max_abs\": 0"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace glint
