// glTF materials completed (io/mesh_materials.h, io/gltf_subset.h, materials/surface_maps.h):
// the metallic-roughness and occlusion textures, KHR_materials_emissive_strength, the sampler's
// wrap modes and the texCoord sets, each rendered from a small file with a known answer; and the
// one warning that names what a file holds and Glint does not render.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "accel/accelerator.h"
#include "film/image_file.h"
#include "io/gltf_scene.h"
#include "io/gltf_subset.h"
#include "io/mesh_io.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

using Corners = std::array<float, 8>;  // (u, v) at the square's corners (0,0) (1,0) (1,1) (0,1)

// glTF's (u, v) running with the square: u = x, v = 1 − y (v runs down the image).
constexpr Corners kUnitUvs = {0, 1, 1, 1, 1, 0, 0, 0};

// A glTF file of one unit square at z = 0, x, y ∈ [0, 1], drawn with material 0 of `materials`
// (a JSON array), its TEXCOORD_0 `uv0` and, where given, TEXCOORD_1 `uv1`; `textures` holds the
// file's "textures", "images" and "samplers" members (with their leading comma).
std::string square(const std::string& materials, const Corners& uv0,
                   const std::optional<Corners>& uv1, const std::string& textures) {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(uv0.data()), 32);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  if (uv1) buffer.append(reinterpret_cast<const char*>(uv1->data()), 32);
  const std::string attributes = uv1 ? R"({"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 3})"
                                     : R"({"POSITION": 0, "TEXCOORD_0": 1})";
  return R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": )" +
         attributes + R"(, "indices": 2, "material": 0}]}],
    "materials": )" +
         materials + textures + R"(,
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
      {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12},
                    {"buffer": 0, "byteOffset": 92, "byteLength": 32}],
    "buffers": [{"byteLength": )" +
         std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

// The square of `file` seen head on by an orthographic camera that it fills, `pixels` wide and
// high, one sample at each pixel's centre; `render` adds "render" keys (after a comma) and
// `lights` fills "lights".
Film renderSquare(const std::string& file, int pixels, const std::string& render,
                  const std::string& lights) {
  const std::string text = R"({"render": {"width": )" + std::to_string(pixels) + R"(, "height": )" +
                           std::to_string(pixels) + R"(, "spp": 1, "sampler": "regular")" + render +
                           R"(},
    "camera": {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0],
               "height": 1},
    "lights": [)" + lights +
                           R"(],
    "objects": [{"type": "mesh", "file": ")" +
                           file + R"("}]})";
  const std::string path = test::writeTemp(file + ".json", text);
  const Scene scene = loadSceneText(text, path, test::tempDir().string());
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(scene, *accel, opt).film;
}

// sRGB's decoding (IEC 61966-2-1): what a colour texture's 8-bit code reads as.
double srgbToLinear(int code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// An 8 × 8 PNG of four 4 × 4 quadrants of the RGB codes `quadrant` (top left, top right,
// bottom left, bottom right), written as `name`.
void writeQuadrants(const std::string& name, const std::array<std::array<int, 3>, 4>& quadrant) {
  std::vector<uint16_t> codes;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c)
        codes.push_back(uint16_t(quadrant[size_t((y / 4) * 2 + x / 4)][size_t(c)]));
  writeRgbImage((test::tempDir() / name).string(), 8, 8, 8, codes);
}

// Pixels of a 16 × 16 render of the unit square whose centres lie in the middle of each
// quadrant of an 8 × 8 image spread over it: a pixel is half a texel, so a bicubic lookup
// there reads that quadrant's texels only (its four taps around texel 2.25 stay inside).
constexpr int kQuadrantPixels[4][2] = {{4, 4}, {11, 4}, {4, 11}, {11, 11}};

TEST(GltfMaterials, AMetallicRoughnessTextureSplitsTheSurfacePerTexel) {
  // Left half: blue 0 (dielectric), green 255 (roughness 1); right half: blue 128 (metallic
  // 128/255, read as data: sRGB would decode it to 0.216), green 0 (a sharp mirror).
  writeQuadrants("metal_rough.png", {{{0, 255, 0}, {0, 0, 128}, {0, 255, 0}, {0, 0, 128}}});
  const std::string file = "metal_rough.gltf";
  test::writeTemp(file, square(R"([{"pbrMetallicRoughness": {
      "baseColorFactor": [0.8, 0.5, 0.2, 1], "metallicFactor": 1, "roughnessFactor": 1,
      "metallicRoughnessTexture": {"index": 0}}}])",
                               kUnitUvs, std::nullopt,
                               R"(, "textures": [{"source": 0}],
                                  "images": [{"uri": "metal_rough.png"}])"));
  // A unit light 45° off the normal (cos 0.70711), and a background the mirror shows.
  const Film film = renderSquare(file, 16, R"(, "background": [0.1, 0.2, 0.3])",
                                 R"({"type": "directional", "direction": [-1, 0, -1],
                                     "intensity": [1, 1, 1]})");
  const double base[3] = {0.8, 0.5, 0.2}, background[3] = {0.1, 0.2, 0.3};
  const double cosL = std::sqrt(0.5), cosH = std::cos(M_PI / 8);  // n·h: h halfway to the eye
  // Left, m = 0, r = 1: k_d = b, the 4 % highlight with exponent 2/1 − 2 → 1 (clamped), no
  // mirror: b·cos + 0.04·cos(22.5°).
  // Right, m = 128/255, r = 0: k_d = b(1 − m); the highlight's exponent 10⁴ leaves nothing
  // 22.5° off; k_m = b·m mirrors the background.
  const double m = 128.0 / 255;
  for (int c = 0; c < 3; ++c) {
    const double left = base[c] * cosL + 0.04 * cosH;
    const double right = base[c] * (1 - m) * cosL + base[c] * m * background[c];
    // Filter weights round in float: 1e-5.
    EXPECT_NEAR(film.pixel(4, 4)[c], left, 1e-5) << c;
    EXPECT_NEAR(film.pixel(4, 11)[c], left, 1e-5) << c;
    EXPECT_NEAR(film.pixel(11, 4)[c], right, 1e-5) << c;
    EXPECT_NEAR(film.pixel(11, 11)[c], right, 1e-5) << c;
  }
}

TEST(GltfMaterials, OcclusionScalesTheAmbientTermOnlyByItsStrength) {
  // Red 0 on the left, 128 on the right (data: 128/255).
  writeQuadrants("occlusion.png", {{{0, 0, 0}, {128, 0, 0}, {0, 0, 0}, {128, 0, 0}}});
  const double base[3] = {0.8, 0.6, 0.4}, ambient = 0.5, occlusion = 128.0 / 255;
  for (const double strength : {1.0, 0.5}) {
    const std::string file = "occlusion_" + std::to_string(int(strength * 10)) + ".gltf";
    test::writeTemp(file, square(R"([{"pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 1},
        "occlusionTexture": {"index": 0, "strength": )" +
                                     std::to_string(strength) + "}}]",
                                 kUnitUvs, std::nullopt,
                                 R"(, "textures": [{"source": 0}],
                                    "images": [{"uri": "occlusion.png"}])"));
    // Ambient 0.5 and a unit light head on: k_d + 0.04 (the highlight, 1 head on) directly,
    // plus the ambient term k_d·0.5 times 1 + strength·(R − 1).
    const Film film = renderSquare(file, 16, R"(, "ambient": [0.5, 0.5, 0.5])",
                                   R"({"type": "directional", "direction": [0, 0, -1],
                                       "intensity": [1, 1, 1]})");
    for (int c = 0; c < 3; ++c) {
      const double direct = base[c] + 0.04;
      const double left = direct + base[c] * ambient * (1 - strength);  // R = 0
      const double right = direct + base[c] * ambient * (1 + strength * (occlusion - 1));
      EXPECT_NEAR(film.pixel(4, 8)[c], left, 1e-5) << strength << " " << c;
      EXPECT_NEAR(film.pixel(11, 8)[c], right, 1e-5) << strength << " " << c;
    }
  }
}

TEST(GltfMaterials, EmissiveStrengthMultipliesTheEmissiveFactor) {
  test::writeTemp("emissive_strength.gltf",
                  square(R"([{"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
                  "emissiveFactor": [0.5, 0.25, 0.1],
                  "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}])",
                         kUnitUvs, std::nullopt, ""));
  // No light: a black base shows its emission alone, 4 × the factor.
  const Film film = renderSquare("emissive_strength.gltf", 4, "", "");
  const double expected[3] = {2, 1, 0.4};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(film.pixel(2, 2)[c], expected[c], 1e-6) << c;
}

// Codes of the quadrants the wrap tests read, and which one a pixel should show.
constexpr std::array<std::array<int, 3>, 4> kWrapQuadrants = {
    {{{200, 40, 40}}, {{40, 200, 40}}, {{40, 40, 200}}, {{200, 200, 40}}}};

TEST(GltfMaterials, TheSamplersWrapModesReadKnownTexelsOutsideTheImage) {
  writeQuadrants("wrap.png", kWrapQuadrants);
  // u and glTF's v run from −1 to 2 across the square (x, and y downwards): three image widths.
  // 48 pixels across make a pixel half a texel; pixel i's centre is at
  // u = −1 + (i + 0.5)/16, and i = 3 + 8j lie a quarter texel off a half's middle:
  // u = −0.78, −0.28, 0.22, 0.72, 1.22, 1.72.
  const Corners wide = {-1, 2, 2, 2, 2, -1, -1, -1};
  // Which half (0 first, 1 second) of the image each of those reads, per wrap mode: REPEAT
  // repeats; CLAMP_TO_EDGE extends the first half's edge below 0 and the second's above 1;
  // MIRRORED_REPEAT reads [−1, 0) and [1, 2) backwards.
  const std::map<int, std::array<int, 6>> halves = {
      {10497, {0, 1, 0, 1, 0, 1}}, {33071, {0, 0, 0, 1, 1, 1}}, {33648, {1, 0, 0, 1, 1, 0}}};
  for (const auto& [wrapS, wrapT] :
       {std::pair{10497, 10497}, std::pair{33071, 33648}, std::pair{33648, 33071}}) {
    const std::string file =
        "wrap_" + std::to_string(wrapS) + "_" + std::to_string(wrapT) + ".gltf";
    test::writeTemp(
        file, square(R"([{"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
                                      "emissiveFactor": [1, 1, 1],
                                      "emissiveTexture": {"index": 0}}])",
                     wide, std::nullopt,
                     R"(, "textures": [{"source": 0, "sampler": 0}],
                                    "images": [{"uri": "wrap.png"}],
                                    "samplers": [{"wrapS": )" +
                         std::to_string(wrapS) + R"(, "wrapT": )" + std::to_string(wrapT) + "}]"));
    // No light, a black base: each pixel is the emissive texel, sRGB-decoded.
    const Film film = renderSquare(file, 48, "", "");
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        const int column = halves.at(wrapS)[size_t(i)], row = halves.at(wrapT)[size_t(j)];
        const auto& codes = kWrapQuadrants[size_t(row * 2 + column)];
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(film.pixel(3 + 8 * i, 3 + 8 * j)[c], srgbToLinear(codes[size_t(c)]), 1e-5)
              << file << " pixel (" << 3 + 8 * i << ", " << 3 + 8 * j << ") channel " << c;
      }
  }
}

TEST(GltfMaterials, ATextureWithTexCoordOneReadsTheSecondSet) {
  writeQuadrants("sets.png", kWrapQuadrants);
  // TEXCOORD_0 is one point, (0.25, 0.25): the middle of the top left quadrant everywhere (the
  // bicubic's taps, texels 0 to 3, stay in it); TEXCOORD_1 spreads the image over the square.
  const Corners point = {0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f};
  for (const int set : {0, 1}) {
    const std::string file = "sets_" + std::to_string(set) + ".gltf";
    test::writeTemp(file, square(R"([{"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
                                      "emissiveFactor": [1, 1, 1],
                                      "emissiveTexture": {"index": 0, "texCoord": )" +
                                     std::to_string(set) + "}}]",
                                 point, kUnitUvs,
                                 R"(, "textures": [{"source": 0}],
                                    "images": [{"uri": "sets.png"}])"));
    const Film film = renderSquare(file, 16, "", "");
    for (int q = 0; q < 4; ++q) {
      const auto& codes = kWrapQuadrants[size_t(set == 1 ? q : 0)];
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(film.pixel(kQuadrantPixels[q][0], kQuadrantPixels[q][1])[c],
                    srgbToLinear(codes[size_t(c)]), 1e-5)
            << "texCoord " << set << " quadrant " << q << " channel " << c;
    }
  }
}

TEST(GltfMaterials, HostileTextureInfosAndSamplersAreWarnedAboutNotTrusted) {
  // A metallic-roughness or occlusion texture past the file's textures makes every texture go
  // (Assimp's reader trusts the indices), as a base colour texture's does.
  for (const char* slot : {R"("pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 3}})",
                           R"("occlusionTexture": {"index": 3})"}) {
    testing::internal::CaptureStderr();
    const nlohmann::json subset = nlohmann::json::parse(gltfSubset(
        "hostile.gltf", std::string(R"({"asset": {"version": "2.0"}, "materials": [{)") + slot +
                            R"(}], "textures": [{"source": 0}], "images": [{"uri": "a.png"}]})"));
    const std::string warnings = testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("its textures are malformed"), std::string::npos) << warnings;
    EXPECT_FALSE(subset.contains("textures")) << subset.dump();
    EXPECT_EQ(subset.dump().find("Texture"), std::string::npos) << subset.dump();
  }
  // A wrap mode glTF does not define, and texCoord 7, are named and read as REPEAT and set 0.
  testing::internal::CaptureStderr();
  std::vector<GltfMaterialInfo> materials;
  gltfSubset("hostile.gltf", R"({"asset": {"version": "2.0"},
    "materials": [{"emissiveTexture": {"index": 0, "texCoord": 7}}],
    "textures": [{"source": 0, "sampler": 0}], "images": [{"uri": "a.png"}],
    "samplers": [{"wrapS": 12345, "wrapT": "clamp"}]})",
             &materials);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_NE(warnings.find("wrapS 12345 is not a glTF wrap mode"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("wrapT \"clamp\" is not a glTF wrap mode"), std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("texCoord 7 is not read"), std::string::npos) << warnings;
  ASSERT_EQ(materials.size(), 1u);
  EXPECT_EQ(materials[0].emissiveUv.wrapS, TextureWrap::Repeat);
  EXPECT_EQ(materials[0].emissiveUv.wrapT, TextureWrap::Repeat);
  EXPECT_EQ(materials[0].emissiveUv.uvSet, 0);
}

// The warnings loading `path` gives.
std::string warningsLoading(const std::string& path) {
  testing::internal::CaptureStderr();
  loadMeshFile(path, false);
  return testing::internal::GetCapturedStderr();
}

size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(GltfMaterials, ClearCoatTestNamesEachDroppedFeatureInOneWarning) {
  const std::string path = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const std::string warnings = warningsLoading(path);
  EXPECT_EQ(occurrences(warnings, "Glint does not render"), 1u) << warnings;
  // Six of its materials carry KHR_materials_clearcoat, three of them with its textures (one
  // each); their six normalTextures are read (materials/normal_map.h), so not named.
  EXPECT_NE(warnings.find("KHR_materials_clearcoat (6 materials, with its clearcoatTexture, "
                          "clearcoatRoughnessTexture, clearcoatNormalTexture)"),
            std::string::npos)
      << warnings;
  EXPECT_EQ(warnings.find("normalTexture (6"), std::string::npos) << warnings;
}

TEST(GltfMaterials, ReadingAFilesCamerasAndLightsLeavesTheWarningToTheMeshReader) {
  // A .gltf rendered as the scene is read twice, for its cameras and lights and then as the
  // mesh: the warning was printed twice.
  const std::string path = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  testing::internal::CaptureStderr();
  readGltfSceneInfo(path);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(warnings, "");
}

TEST(GltfMaterials, EveryDroppedFeatureOfAFileIsNamedOnceAndRenderedOnesAreNot) {
  // Sheen with a texture, variants, a skin, two animations, a morphed primitive and a line
  // primitive; transmission (rendered) with its texture (not read); emissive strength and
  // texture transforms rendered.
  const std::string text = R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_materials_sheen", "KHR_materials_variants",
                       "KHR_materials_transmission", "KHR_texture_transform",
                       "KHR_materials_emissive_strength"],
    "materials": [
      {"extensions": {"KHR_materials_sheen": {"sheenColorTexture": {"index": 0}}}},
      {"extensions": {"KHR_materials_sheen": {}, "KHR_materials_transmission":
        {"transmissionFactor": 1, "transmissionTexture": {"index": 0}}}},
      {"extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}}],
    "meshes": [{"primitives": [{"attributes": {}, "targets": [{}]}, {"attributes": {}, "mode": 1}]}],
    "skins": [{"joints": [0]}], "animations": [{}, {}]})";
  testing::internal::CaptureStderr();
  std::vector<GltfMaterialInfo> materials;
  gltfSubset("dropped.gltf", text, &materials);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(occurrences(warnings, "Glint does not render"), 1u) << warnings;
  for (const char* named :
       {"KHR_materials_sheen (2 materials, with its sheenColorTexture)",
        "KHR_materials_transmission's transmissionTexture (1 material)", "KHR_materials_variants",
        "1 skin", "morph targets (on 1 primitive)", "2 animations", "1 point or line primitive"})
    EXPECT_EQ(occurrences(warnings, named), 1u) << named << ": " << warnings;
  for (const char* rendered :
       {"KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_transmission ("})
    EXPECT_EQ(occurrences(warnings, rendered), 0u) << rendered << ": " << warnings;
}

TEST(GltfMaterials, AnEmissiveStrengthGlintCannotUseIsNamedAndReadAsOne) {
  // glTF's emissiveStrength is a number of at least 0. Past float's range (1e39), negative or
  // not a number, it was read as 1 (or clamped to 0) without a word; it is now 1, the
  // extension's default, with a warning naming the material and the value.
  const auto strength = [](const std::string& value) {
    return R"({"extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": )" + value +
           "}}}";
  };
  const std::string text =
      R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_emissive_strength"],
      "materials": [)" +
      strength("0") + ", " + strength("3") + ", " + strength("1e39") + ", " + strength("-2") +
      ", " + strength(R"("x")") + "]}";
  testing::internal::CaptureStderr();
  std::vector<GltfMaterialInfo> materials;
  gltfSubset("strength.gltf", text, &materials);
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_EQ(materials.size(), 5u);
  const float expected[5] = {0, 3, 1, 1, 1};
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(materials[i].emissiveStrength, expected[i]) << i;
  for (const char* named :
       {"materials[2]: KHR_materials_emissive_strength's emissiveStrength "
        "1e+39 is not a number from 0 to 3.4e38: 1 is used",
        "materials[3]: KHR_materials_emissive_strength's emissiveStrength -2",
        R"(materials[4]: KHR_materials_emissive_strength's emissiveStrength "x")"})
    EXPECT_EQ(occurrences(warnings, named), 1u) << named << ": " << warnings;
  EXPECT_EQ(occurrences(warnings, "emissiveStrength"), 3u) << warnings;
}

TEST(GltfMaterials, ATextureWithoutASourceImageIsNamed) {
  // A texture whose image only an extension names (here KHR_texture_basisu) was dropped by
  // Assimp without a word.
  const std::string text = R"({"asset": {"version": "2.0"}, "images": [{"uri": "a.png"}],
      "textures": [{"source": 0}, {"extensions": {"KHR_texture_basisu": {"source": 0}}}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}}]})";
  testing::internal::CaptureStderr();
  gltfSubset("sourceless.gltf", text);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(occurrences(warnings,
                        "sourceless.gltf: 1 texture(s), textures[1] first, name no "
                        "source image Glint reads"),
            1u)
      << warnings;
}

TEST(GltfMaterials, AnOcclusionStrengthOutsideZeroToOneIsNamedAndClamped) {
  // glTF's occlusion strength is from 0 to 1; 1e30 was clamped to 1 without a word.
  const auto occlusion = [](const std::string& value) {
    return R"({"occlusionTexture": {"index": 0, "strength": )" + value + "}}";
  };
  const std::string text = R"({"asset": {"version": "2.0"}, "textures": [{"source": 0}],
      "images": [{"uri": "o.png"}], "materials": [)" +
                           occlusion("0.5") + ", " + occlusion("1e30") + ", " + occlusion("-1") +
                           ", " + occlusion(R"("x")") + "]}";
  testing::internal::CaptureStderr();
  std::vector<GltfMaterialInfo> materials;
  gltfSubset("occlusion.gltf", text, &materials);
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_EQ(materials.size(), 4u);
  const float expected[4] = {0.5f, 1, 0, 0};
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(materials[i].occlusionStrength, expected[i]) << i;
  for (const char* named : {"materials[1]: occlusionTexture's strength 1e+30 is not a number "
                            "from 0 to 1: 1 is used",
                            "materials[2]: occlusionTexture's strength -1 is not a number from 0 "
                            "to 1: 0 is used",
                            R"(materials[3]: occlusionTexture's strength "x")"})
    EXPECT_EQ(occurrences(warnings, named), 1u) << named << ": " << warnings;
  EXPECT_EQ(occurrences(warnings, "strength"), 3u) << warnings;
}

}  // namespace
}  // namespace glint
