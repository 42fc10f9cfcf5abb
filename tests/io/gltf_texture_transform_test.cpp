// glTF's KHR_texture_transform on the base colour and emissive textures
// (io/gltf_texture_transform.h): the transform in Glint's (u, v), the materials of a file that
// Assimp numbers in another order, hostile values, and rendered pixels that show the texel the
// extension names.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <vector>

#include "accel/accelerator.h"
#include "film/image_file.h"
#include "gltf_util.h"
#include "io/gltf_subset.h"
#include "io/gltf_texture_transform.h"
#include "io/mesh_io.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

using nlohmann::json;

constexpr double kHalfPi = 1.5707963267948966;

// The glTF image coordinates (s, t) of glTF texture coordinates (u, v), written out as the
// extension's prose and example have it (T·R·S; R turns counter-clockwise in a space whose v runs
// down): the reference the conversion is checked against.
Vec2f gltfSpec(Vec2f uv, Vec2f offset, double rotation, Vec2f scale) {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double su = scale.x * uv.x, sv = scale.y * uv.y;
  return {float(c * su + s * sv + offset.x), float(-s * su + c * sv + offset.y)};
}

// Where Glint reads an image for a surface point of texture coordinates uv through t.
Vec2f glintSt(Vec2f uv, const UvTransform& t) {
  ShadingPoint sp;
  sp.ng = sp.ns = {0, 0, 1};
  sp.uv = uv;
  sp.dpdu = {1, 0, 0};
  sp.dpdv = {0, 1, 0};
  return imageFootprint(sp, {0, 0, 1}, 0.01f, t).st;
}

// Expects t's matrix [[m00, m01], [m10, m11]] and offset (x, y) to be `expected`, each within
// `tolerance`.
void expectTransform(const UvTransform& t, const std::array<float, 6>& expected, double tolerance) {
  const float actual[6] = {t.m00, t.m01, t.m10, t.m11, t.offset.x, t.offset.y};
  const char* names[6] = {"m00", "m01", "m10", "m11", "offset.x", "offset.y"};
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << names[i];
}

TEST(GltfTextureTransform, GlintReadsTheTexelTheExtensionNamesByHand) {
  // offset (0.25, 0.1), rotation π/2, scale (0.5, 2). Glint's (u, v) = (0.2, 0.3) is glTF's
  // (0.2, 1 − 0.3) = (0.2, 0.7) (Assimp flips v). The extension: S → (0.1, 1.4); R(π/2) with
  // cos 0, sin 1 → (0·0.1 + 1·1.4, −1·0.1 + 0·1.4) = (1.4, −0.1); T → (s, t) = (1.65, 0.0).
  const UvTransform t = uvTransformFromGltf({0.25f, 0.1f}, float(kHalfPi), {0.5f, 2});
  const Vec2f st = glintSt({0.2f, 0.3f}, t);
  EXPECT_NEAR(st.x, 1.65f, 1e-6);  // float rounding of cos(π/2) ≈ −4e-8 and of the sums
  EXPECT_NEAR(st.y, 0.0f, 1e-6);
  // Glint's own (u', v') is then (1.65, 1 − 0.0): the matrix [[c·su, −s·sv], [s·su, c·sv]] =
  // [[0, −2], [0.5, 0]] and the offset (o_u + s·sv, 1 − o_v − c·sv) = (2.25, 0.9).
  expectTransform(t, {0.0f, -2.0f, 0.5f, 0.0f, 2.25f, 0.9f}, 1e-7);
}

TEST(GltfTextureTransform, GlintReadsTheTexelTheExtensionNamesEverywhere) {
  // The extension's README example (offset [0, 1], rotation π/2, scale ½) "utilizes only the
  // lower left quadrant": glTF (u, v) ∈ [0, 1]² reads s = v/2 ∈ [0, ½], t = 1 − u/2 ∈ [½, 1].
  const UvTransform example = uvTransformFromGltf({0, 1}, float(kHalfPi), {0.5f, 0.5f});
  for (float u : {0.0f, 0.5f, 1.0f})
    for (float v : {0.0f, 0.5f, 1.0f}) {
      const Vec2f st = glintSt({u, 1 - v}, example);  // Glint's v of glTF's v
      EXPECT_NEAR(st.x, v / 2, 1e-6) << u << " " << v;
      EXPECT_NEAR(st.y, 1 - u / 2, 1e-6) << u << " " << v;
    }
  // Any transform, at a grid of points: F∘A∘F in Glint gives the reference's (s, t) up to
  // float rounding (values up to ~10: 1e-5).
  const Vec2f offsets[] = {{0, 0}, {0.3f, -0.7f}, {2.5f, 1.25f}};
  const double rotations[] = {0, 0.3, -2.0, kHalfPi};
  const Vec2f scales[] = {{1, 1}, {0.5f, 3}, {-1, 2}};
  for (Vec2f offset : offsets)
    for (double rotation : rotations)
      for (Vec2f scale : scales) {
        const UvTransform t = uvTransformFromGltf(offset, float(rotation), scale);
        for (float u = 0; u <= 1; u += 0.25f)
          for (float v = 0; v <= 1; v += 0.25f) {
            const Vec2f want = gltfSpec({u, v}, offset, float(rotation), scale);
            const Vec2f st = glintSt({u, 1 - v}, t);
            EXPECT_NEAR(st.x, want.x, 1e-5) << rotation << " at " << u << ", " << v;
            EXPECT_NEAR(st.y, want.y, 1e-5) << rotation << " at " << u << ", " << v;
          }
      }
}

// The warning `extension` (JSON) gives, and the transform: "" when there is none.
std::string warningOf(const std::string& extension, UvTransform* t = nullptr) {
  testing::internal::CaptureStderr();
  const UvTransform got = gltfTextureTransform(json::parse(extension), "material 0");
  if (t) *t = got;
  return testing::internal::GetCapturedStderr();
}

bool isIdentity(const UvTransform& t) {
  return t.m00 == 1 && t.m01 == 0 && t.m10 == 0 && t.m11 == 1 && t.offset.x == 0 && t.offset.y == 0;
}

TEST(GltfTextureTransform, MalformedOrAbsurdValuesAreWarnedAboutAndIgnored) {
  // Each is refused whole (the texture is read untransformed: the identity), with a warning
  // naming the value. (JSON has no infinities: nlohmann refuses 1e400, and the file with it.)
  for (const char* bad :
       {R"("offset")", R"({"offset": []})", R"({"offset": [1]})", R"({"offset": [1, 2, 3]})",
        R"({"offset": ["0", 0]})", R"({"offset": [1e300, 0]})", R"({"scale": [1e5, 1]})",
        R"({"scale": null})", R"({"rotation": "1.5"})", R"({"rotation": -1e300})",
        R"({"rotation": 20000})"}) {
    UvTransform t = uvTransformFromGltf({0.5f, 0.5f}, 1, {2, 2});
    const std::string warning = warningOf(bad, &t);
    EXPECT_NE(warning.find("material 0: KHR_texture_transform ignored"), std::string::npos)
        << bad << ": " << warning;
    EXPECT_TRUE(isIdentity(t)) << bad;
  }
  // Within the bounds, and the extension's own extensions and extras, are read quietly.
  UvTransform t;
  EXPECT_EQ(warningOf(R"({"offset": [-10000, 0.5], "scale": [0, -3], "rotation": 6.2,
                          "extras": {}, "extensions": {}})",
                      &t),
            "");
  EXPECT_FALSE(isIdentity(t));
  EXPECT_EQ(warningOf("null", &t), "");  // no extension
  EXPECT_TRUE(isIdentity(t));
}

TEST(GltfTextureTransform, ItsTexCoordChoosesTheSetAndAThirdSetIsWarnedAbout) {
  // The extension's texCoord replaces the textureInfo's: 1 reads TEXCOORD_1 quietly, with the
  // offset (0.25, 0) → Glint's offset (0.25, 1 − 0 − 1) = (0.25, 0).
  UvTransform t;
  EXPECT_EQ(warningOf(R"({"offset": [0.25, 0], "texCoord": 1})", &t), "");
  EXPECT_EQ(t.uvSet, 1);
  EXPECT_FLOAT_EQ(t.offset.x, 0.25f);
  EXPECT_FLOAT_EQ(t.offset.y, 0.0f);
  EXPECT_EQ(warningOf(R"({"offset": [0.25, 0], "texCoord": 0})", &t), "");
  EXPECT_EQ(t.uvSet, 0);
  // Glint reads two sets: texCoord 2 is ignored, the transform kept on the textureInfo's set.
  const std::string warning = warningOf(R"({"offset": [0.25, 0], "texCoord": 2})", &t);
  EXPECT_NE(warning.find("texCoord 2 is not read (Glint reads TEXCOORD_0 and TEXCOORD_1)"),
            std::string::npos)
      << warning;
  EXPECT_EQ(t.uvSet, 0);
  EXPECT_FLOAT_EQ(t.offset.x, 0.25f);
}

// A 32 × 32 RGB image of 4 × 4 regions of 8 × 8 texels, region (column c, row r) counted from
// the top left holding the sRGB codes (30 + 60c, 30 + 60r, 100): sixteen colours. A bicubic
// lookup within 2 texels of a region's centre reads that region's texels only.
constexpr int kRegionTexels = 8, kRegions = 4;
int regionCode(int column, int row, int channel) {
  return channel == 0 ? 30 + 60 * column : channel == 1 ? 30 + 60 * row : 100;
}

std::string writeRegionsImage() {
  static const std::string path = [] {
    const std::string p = (test::tempDir() / "regions.png").string();
    std::vector<uint16_t> codes;
    for (int y = 0; y < kRegions * kRegionTexels; ++y)
      for (int x = 0; x < kRegions * kRegionTexels; ++x)
        for (int c = 0; c < 3; ++c)
          codes.push_back(uint16_t(regionCode(x / kRegionTexels, y / kRegionTexels, c)));
    writeRgbImage(p, kRegions * kRegionTexels, kRegions * kRegionTexels, 8, codes);
    return p;
  }();
  return path;
}

// sRGB's decoding (IEC 61966-2-1), as OCIO linearises 8-bit PNG textures.
double srgbToLinear(int code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// A textureInfo of texture 0 with the extension `transform` (JSON; none where empty).
std::string textureInfo(const std::string& transform) {
  return R"({"index": 0)" +
         (transform.empty() ? std::string()
                            : R"(, "extensions": {"KHR_texture_transform": )" + transform + "}") +
         "}";
}

TEST(GltfTextureTransform, EachMaterialGetsItsOwnTransformWhateverOrderAssimpGivesThem) {
  writeRegionsImage();
  // Square 0 draws with material 1, square 1 with material 0: Assimp numbers material 1 first.
  // Material 0 shifts its base colour by offset (0.5, 0): in Glint the identity matrix and the
  // offset (0.5, 1 − 0 − 1) = (0.5, 0). Material 1 is a metal MASK whose base colour (its kd,
  // km and cut-out) and emission turn by π/2: in Glint [[0, −1], [1, 0]] and the offset
  // (0 + 1·1, 1 − 0 − 0·1) = (1, 1).
  const std::string transformed = textureInfo(R"({"rotation": 1.5707963267948966})");
  const std::string path = test::writeTemp(
      "two_materials.gltf", test::gltfSquares({1, 0},
                                              R"([
        {"name": "shifted", "pbrMetallicRoughness": {"metallicFactor": 0, "baseColorTexture": )" +
                                                  textureInfo(R"({"offset": [0.5, 0]})") + R"(}},
        {"name": "turned", "alphaMode": "MASK", "emissiveFactor": [1, 1, 1],
         "emissiveTexture": )" + transformed +
                                                  R"(, "pbrMetallicRoughness": {"metallicFactor": 1,
         "baseColorTexture": )" + transformed + "}}]"));
  const MeshFile file = loadMeshFile(path);
  ASSERT_EQ(file.materials.size(), 2u);
  for (const Material& m : file.materials) {
    if (m.name == "two_materials.gltf:shifted") {
      const UvTransform& t = m.surface.kd.uvTransform;
      ASSERT_EQ(m.surface.kd.pattern, TexturePattern::Image);
      expectTransform(t, {1, 0, 0, 1, 0.5f, 0.0f}, 1e-7);
      EXPECT_TRUE(isIdentity(m.surface.ke.uvTransform));  // no emission texture
    } else {
      EXPECT_EQ(m.name, "two_materials.gltf:turned");
      ASSERT_EQ(m.surface.km.pattern, TexturePattern::Image);
      ASSERT_EQ(m.surface.ke.pattern, TexturePattern::Image);
      ASSERT_TRUE(m.cutout.image);
      for (const UvTransform* t : {&m.surface.kd.uvTransform, &m.surface.km.uvTransform,
                                   &m.surface.ke.uvTransform, &m.cutout.uvTransform}) {
        EXPECT_NEAR(t->m00, 0, 1e-7);  // cos(π/2) in double, rounded to float
        EXPECT_NEAR(t->m01, -1, 1e-7);
        EXPECT_NEAR(t->m10, 1, 1e-7);
        EXPECT_NEAR(t->m11, 0, 1e-7);
        EXPECT_NEAR(t->offset.x, 1, 1e-7);
        EXPECT_NEAR(t->offset.y, 1, 1e-7);
      }
    }
  }
  // Assimp is given neither the extension (its reader indexes offset and scale without checking
  // their sizes) nor the names, which it gets as tags of the materials' indices.
  std::vector<GltfMaterialInfo> infos;
  const json subset = json::parse(gltfSubset("m.gltf", test::readFile(path), &infos));
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[0].name, "shifted");
  EXPECT_EQ(infos[1].name, "turned");
  EXPECT_EQ(subset["materials"][1]["name"], gltfMaterialTag(1));
  EXPECT_EQ(gltfMaterialIndex(gltfMaterialTag(1)), 1u);
  EXPECT_EQ(gltfMaterialIndex("turned"), std::nullopt);
  EXPECT_EQ(subset["materials"][1]["emissiveTexture"], json::parse(R"({"index": 0})"));
  EXPECT_EQ(subset.dump().find("KHR_texture_transform\":{"), std::string::npos);
}

TEST(GltfTextureTransform, AMaterialWithoutANameKeepsNone) {
  // Its tag is not its name: the Glint material is "FILE:" as before.
  writeRegionsImage();
  const MeshFile file = loadMeshFile(test::writeTemp(
      "unnamed.gltf", test::gltfSquares({0}, "[{" + std::string(R"("pbrMetallicRoughness": {
        "baseColorTexture": )") + textureInfo(R"({"scale": [2, 2]})") +
                                                 "}}]")));
  ASSERT_EQ(file.materials.size(), 1u);
  EXPECT_EQ(file.materials[0].name, "unnamed.gltf:");
  EXPECT_NEAR(file.materials[0].surface.kd.uvTransform.m00, 2, 1e-7);
}

TEST(GltfTextureTransform, KhronosSampleModelKeepsEachMaterialsTransform) {
  // Khronos's TextureTransformTest (Assimp's test models), nine materials. Rendered, every arrow
  // points at its green marker (not the red one of the opposite turn, nor the yellow one of no
  // transform). Here its materials' transforms, by hand, in Glint's (u, v):
  const MeshFile file =
      loadMeshFile("/usr/share/assimp/models/glTF2/textureTransform/TextureTransformTest.gltf");
  const auto transformOf = [&](const std::string& name) {
    for (const Material& m : file.materials)
      if (m.name == "TextureTransformTest.gltf:" + name) {
        EXPECT_EQ(m.surface.kd.pattern, TexturePattern::Image) << name;
        return m.surface.kd.uvTransform;
      }
    ADD_FAILURE() << "no material " << name;
    return UvTransform{};
  };
  // "Offset V", offset [0, 0.5]: the identity matrix, offset (0, 1 − 0.5 − 1) = (0, −0.5).
  const UvTransform offsetV = transformOf("Offset V");
  EXPECT_NEAR(offsetV.m00, 1, 1e-7);
  EXPECT_NEAR(offsetV.m11, 1, 1e-7);
  EXPECT_NEAR(offsetV.offset.x, 0, 1e-7);
  EXPECT_NEAR(offsetV.offset.y, -0.5f, 1e-7);
  // "Rotation", π/8: cos 0.9238795, sin 0.3826834; matrix [[cos, −sin], [sin, cos]], offset
  // (sin, 1 − cos) = (0.3826834, 0.0761205).
  const UvTransform rotation = transformOf("Rotation");
  expectTransform(rotation,
                  {0.9238795f, -0.3826834f, 0.3826834f, 0.9238795f, 0.3826834f, 0.0761205f}, 1e-6);
  EXPECT_TRUE(isIdentity(transformOf("Correct")));  // a marker without the extension
}

// Renders the unit square of a one-material glTF file seen head on: 64 × 64 pixels, one sample
// at each pixel's centre, orthographic; a unit light along the normal. Pixel (x, y) (y down)
// sees glTF's u = (x + ½)/64, v = (y + ½)/64. A base colour c (not metallic, roughness 1)
// reads c·1·cos 0 + k_s 0.04 (Blinn-Phong, exponent 1, head on); an emission adds itself.
Film renderSquare(const std::string& material, const std::string& name) {
  writeRegionsImage();
  test::writeTemp(name + ".gltf", test::gltfSquares({0}, "[" + material + "]"));
  const std::string sceneText = R"({
    "render": {"width": 64, "height": 64, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0],
               "height": 1},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": [1, 1, 1]}],
    "objects": [{"type": "mesh", "file": ")" +
                                name + R"(.gltf"}]})";
  const std::string path = test::writeTemp(name + ".json", sceneText);
  const Scene scene = loadSceneText(sceneText, path, test::tempDir().string());
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(scene, *accel, opt).film;
}

// Pixel (x, y) shows region (column, row), linearised, plus `plus`: to float rounding of the
// filter weights (1e-5), since the lookups are within 2 texels of a region's centre (and a
// pixel is at most half a texel, so the filter does not widen).
void expectRegion(const Film& film, int x, int y, int column, int row, double plus,
                  const std::string& what) {
  const float* px = film.pixel(x, y);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(px[c], srgbToLinear(regionCode(column, row, c)) + plus, 1e-5)
        << what << ": pixel (" << x << ", " << y << ") should show region (" << column << ", "
        << row << "), channel " << c;
}

TEST(GltfTextureTransform, OffsetAndScaleShowTheTopRightQuarterOfTheImage) {
  // offset [0.5, 0], scale [0.5, 0.5]: s = u/2 + ½, t = v/2, the top right quarter (regions
  // 2–3 of columns, 0–1 of rows) over the whole square. Pixel 16: u = 16.5/64 → s = 0.6289
  // (texel 20.1 of 32, column 2's centre 20), t = 0.1289 (texel 4.1, row 0's centre 4); pixel
  // 48: s = 0.8789 (28.1, column 3), t = 0.3789 (12.1, row 1). Untransformed, pixel (16, 16)
  // would show region (1, 1).
  const Film film = renderSquare(R"({"pbrMetallicRoughness": {"metallicFactor": 0,
    "baseColorTexture": )" + textureInfo(R"({"offset": [0.5, 0], "scale": [0.5, 0.5]})") +
                                     "}}",
                                 "offset_scale");
  expectRegion(film, 16, 16, 2, 0, 0.04, "offset and scale");
  expectRegion(film, 48, 16, 3, 0, 0.04, "offset and scale");
  expectRegion(film, 16, 48, 2, 1, 0.04, "offset and scale");
  expectRegion(film, 48, 48, 3, 1, 0.04, "offset and scale");
}

TEST(GltfTextureTransform, AQuarterTurnShowsTheImageTurnedClockwise) {
  // rotation π/2: s = v, t = −u (the image repeats: 1 − u). The extension says this turns the
  // image clockwise: the square's top left shows the image's bottom left. Pixels 8, 24, 40, 56
  // are at (p + ½)/64 = 0.133, 0.383, 0.633, 0.883, a quarter texel past the centres of regions
  // 0–3: pixel (x, y) shows column y/16 and row 3 − x/16. The opposite turn (the README's GLSL
  // read literally: s = −v, t = u) would show column 3 − y/16, row x/16.
  const Film film = renderSquare(R"({"pbrMetallicRoughness": {"metallicFactor": 0,
    "baseColorTexture": )" + textureInfo(R"({"rotation": 1.5707963267948966})") +
                                     "}}",
                                 "quarter_turn");
  for (int x : {8, 24, 40, 56})
    for (int y : {8, 24, 40, 56}) expectRegion(film, x, y, y / 16, 3 - x / 16, 0.04, "π/2");
}

TEST(GltfTextureTransform, AnEmissionTextureTurnsAfterItsAnisotropicScale) {
  // emissiveTexture with offset [0.25, 0.5], rotation π/2, scale [0.5, 1] on a black base (k_d
  // 0, k_s 0.04): T·R·S gives s = v + ¼, t = ½ − u/2 (S·R would give s = v/2 + ¼, t = ½ − u).
  // Pixels y = 8, 24, 40, 56 read s = 0.383, 0.633, 0.883, 1.133 (columns 1, 2, 3, 0); x = 16
  // and 48 read t = 0.371 (row 1) and 0.121 (row 0), each within ¼ texel of a centre. Emission
  // 1 × texel, plus the highlight 0.04.
  const Film film = renderSquare(
      R"({"emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1],
        "metallicFactor": 0}, "emissiveTexture": )" +
          textureInfo(R"({"offset": [0.25, 0.5], "rotation": 1.5707963267948966,
                          "scale": [0.5, 1]})") +
          "}",
      "emission");
  for (int x : {16, 48})
    for (int y : {8, 24, 40, 56})
      expectRegion(film, x, y, (y / 16 + 1) % 4, x == 16 ? 1 : 0, 0.04, "emission");
}

}  // namespace
}  // namespace glint
