// Normal and bump maps end to end (issue 42): scene keys, glTF normalTexture and TANGENT, MTL
// norm / bump with -bm, read from real files and rendered through both integrators.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "accel/accelerator.h"
#include "film/image_file.h"
#include "gltf_util.h"
#include "io/mesh_io.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

const double kCos30 = std::sqrt(3.0) / 2;

Film render(const std::string& sceneText, const std::string& name, const std::string& aovs = "") {
  const std::string path = test::writeTemp(name, sceneText);
  const Scene scene = loadSceneText(sceneText, path, test::tempDir().string());
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  if (!aovs.empty()) opt.aovs = AovSet::parse(aovs);
  return renderScene(scene, *accel, opt).film;
}

// A 4 × 4 16-bit PNG of one colour, each channel's code round(c · 65535).
std::string writeConstantImage(const std::string& name, Rgb c) {
  std::vector<uint16_t> codes;
  for (int i = 0; i < 16; ++i)
    for (float v : {c.r, c.g, c.b}) codes.push_back(uint16_t(std::lround(v * 65535)));
  const std::string path = (test::tempDir() / name).string();
  writeRgbImage(path, 4, 4, 16, codes);
  return path;
}

// A 2 × 2 square in the plane y = 0 facing +y, u along +x and v along −z, seen from above by an
// orthographic camera (the square fills the 8 × 8 frame, image up = −z = +v), lit by a unit
// directional light travelling along `lightTravel`; kd 1, nothing else. `maps`: the material's
// extra keys; `geometry`: the scene's objects (and groups) in place of the quad.
constexpr const char* kSquareQuad =
    R"("objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2],
                 "material": "m"}])";

std::string squareScene(const std::string& maps, const std::string& lightTravel,
                        const std::string& geometry = kSquareQuad) {
  return R"({
    "render": {"width": 8, "height": 8, "spp": 1, "sampler": "regular"},
    "camera": {"type": "orthographic", "eye": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
               "height": 2},
    "materials": {"m": {"type": "phong", "kd": [1, 1, 1], "ka": [0, 0, 0])" +
         maps + R"(}},
    "lights": [{"type": "directional", "direction": )" +
         lightTravel + R"(, "intensity": [1, 1, 1]}], )" + geometry + "}";
}

// The texel that encodes tangent-space normal (x, y, z): (m + 1) / 2.
Rgb encoded(double x, double y, double z) {
  return {float((x + 1) / 2), float((y + 1) / 2), float((z + 1) / 2)};
}

TEST(NormalMaps, ANormalMapTiltedThirtyDegreesReadsOneOverCos30OfThePlainSquare) {
  // The map tilts the normal 30° towards +u (+x); the light comes from 30° off the vertical on
  // the +x side, so it falls along the mapped normal: kd · 1 against kd · cos 30° without the
  // map, a ratio of 1/cos 30° = 1.1547. Read otherwise the same texel gives other values: sRGB-
  // decoded, (0.75, 0.5, 0.933) becomes (0.52, 0.21, 0.85), a normal 46° from this light (ratio
  // 0.81); ignored, the ratio is 1; with the tangent mirrored (−u) the normal leans away, 60°
  // from the light (ratio 0.5/cos 30° = 0.577). The bump shadowing term is 1 here (g = 1,
  // materials/normal_map.h). Tolerance: the 16-bit codes move the normal by at most 2e-5 rad,
  // cos by 1e-5 relative; 1e-4.
  const std::string map = writeConstantImage("tilt_u.png", encoded(0.5, 0, kCos30));
  const std::string light = "[-0.5, -0.8660254, 0]";
  const Film plain = render(squareScene("", light), "plain_u.json");
  const Film mapped =
      render(squareScene(R"(, "normal_map": {"image": "tilt_u.png", "scale": 1.0})", light),
             "tilt_u.json", "normal");
  EXPECT_NEAR(plain.pixel(4, 4)[0], kCos30, 1e-5);  // Lambert's cosine, float rounding
  EXPECT_NEAR(mapped.pixel(4, 4)[0] / plain.pixel(4, 4)[0], 1 / kCos30, 1e-4);
  EXPECT_NEAR(mapped.pixel(1, 6)[1] / plain.pixel(1, 6)[1], 1 / kCos30, 1e-4);  // everywhere
  // The normal AOV shows the bent normal, (sin 30°, cos 30°, 0) in the world (pixel (4, 4) of
  // the 8 × 8 plane).
  ASSERT_EQ(mapped.planes().size(), 1u);
  const double* n = &mapped.planes()[0].values[(4 * 8 + 4) * 3];
  EXPECT_NEAR(n[0], 0.5, 1e-4);
  EXPECT_NEAR(n[1], kCos30, 1e-4);
  EXPECT_NEAR(n[2], 0, 1e-4);
}

TEST(NormalMaps, ABentNormalDoesNotLightTheSurfaceFromBelowItsHorizon) {
  // Chiang et al.'s shadowing term (materials/normal_map.h) on the same square, the normal bent
  // 30° towards +u. Light 80° off the vertical on the +u side: the bent normal sees it at 50°,
  // and g = cos 80° / (cos 50° · cos 30°) = 0.3119 fades it to −g³ + g² + g = 0.3789, so the
  // square reads cos 50° · 0.3789 = 0.2436 (0.6428 without the term: the hard terminator the
  // term removes). Light 100° off the vertical, below the square's horizon, still 70° from the
  // bent normal: g < 0, black (cos 70° = 0.34 without the term, lit from behind). Tolerance:
  // the 16-bit map's normal error, 1e-4, times the slopes here, 1e-3.
  writeConstantImage("tilt_u_low.png", encoded(0.5, 0, kCos30));
  const std::string maps = R"(, "normal_map": {"image": "tilt_u_low.png"})";
  const double g = std::cos(80 * M_PI / 180) / (std::cos(50 * M_PI / 180) * kCos30);
  const Film grazing = render(squareScene(maps, "[-0.98480775, -0.17364818, 0]"), "grazing.json");
  EXPECT_NEAR(grazing.pixel(4, 4)[0], std::cos(50 * M_PI / 180) * (-g * g * g + g * g + g), 1e-3);
  const Film below = render(squareScene(maps, "[-0.98480775, 0.17364818, 0]"), "below.json");
  EXPECT_EQ(below.pixel(4, 4)[0], 0);
}

TEST(NormalMaps, GreenTiltsTowardsPlusV) {
  // The same with the tilt in green, towards +v (−z, the image's top), and the light from that
  // side: a bitangent turned the wrong way (a DirectX-style map read as glTF's, or a sign lost)
  // would lean the normal 60° from the light, a ratio of 0.577.
  writeConstantImage("tilt_v.png", encoded(0, 0.5, kCos30));
  const std::string light = "[0, -0.8660254, 0.5]";
  const Film plain = render(squareScene("", light), "plain_v.json");
  const Film mapped =
      render(squareScene(R"(, "normal_map": {"image": "tilt_v.png"})", light), "tilt_v.json");
  EXPECT_NEAR(mapped.pixel(4, 4)[0] / plain.pixel(4, 4)[0], 1 / kCos30, 1e-4);
}

TEST(NormalMaps, AMirroringInstanceKeepsGreenTowardsPlusV) {
  // The square as a mesh (u along +x, v along −z, generated tangents) placed by an instance
  // that mirrors x: the tangent turns to −x with the surface, and +v stays −z, now on the other
  // side of normal × tangent, so the bitangent's sign must flip (Scene::tangentFrame). Green
  // tilted 30° towards +v under a light from that side reads 1/cos 30° of the plain square; a
  // sign left as it was would lean the normal 60° from the light (0.577).
  writeConstantImage("tilt_v_mirror.png", encoded(0, 0.5, kCos30));
  const auto scene = [](const std::string& maps) {
    return squareScene(maps, "[0, -0.8660254, 0.5]", R"(
    "groups": {"square": [{"type": "mesh", "material": "m",
      "positions": [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]],
      "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "indices": [[0, 1, 2], [0, 2, 3]]}]},
    "objects": [{"type": "instance", "group": "square", "transform": {"scale": [-1, 1, 1]}}])");
  };
  const Film plain = render(scene(""), "mirror_plain.json");
  const Film mapped =
      render(scene(R"(, "normal_map": {"image": "tilt_v_mirror.png"})"), "mirror_mapped.json");
  EXPECT_NEAR(mapped.pixel(4, 4)[0] / plain.pixel(4, 4)[0], 1 / kCos30, 1e-4);
}

TEST(NormalMaps, ABumpMapRampTiltsTheNormalByItsSlope) {
  // Heights rise linearly along +u: texel i of 64 holds (i + 0.5)/64 (16-bit), so the filtered
  // image is s itself away from the edges, and h = scale · u over the square's 2 units of u:
  // the normal leans back from +u by atan(scale / 2). scale = 2 tan 30° leans it 30° towards
  // −x; lit from 30° off the vertical on the −x side it reads 1/cos 30° of the plain square
  // (and (cos 60°)/cos 30° = 0.577 were the slope's sign wrong). Tolerance: 16-bit codes and
  // the filter's float weights, 1e-3 of the slope.
  std::vector<uint16_t> codes;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) codes.push_back(uint16_t(std::lround((x + 0.5) / 64 * 65535)));
  writeRgbImage((test::tempDir() / "bump_ramp.png").string(), 64, 4, 16, codes);
  const std::string light = "[0.5, -0.8660254, 0]";
  const Film plain = render(squareScene("", light), "plain_bump.json");
  const Film bumped =
      render(squareScene(R"(, "bump_map": {"image": "bump_ramp.png", "scale": 1.1547005})", light),
             "bumped.json");
  // Pixels 2 … 5 of 8 across: s in (0.25, 0.75), away from the ramp's wrap at s = 0 / 1.
  for (int x = 2; x <= 5; ++x)
    EXPECT_NEAR(bumped.pixel(x, 4)[0] / plain.pixel(x, 4)[0], 1 / kCos30, 1e-3) << x;
}

TEST(NormalMaps, TheSceneKeysAreChecked) {
  const auto errorOf = [](const std::string& material) {
    return test::sceneErrorOf(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": )" + material +
                              R"(}, "objects": []})");
  };
  EXPECT_NE(errorOf(R"({"type": "phong", "normal_map": "n.png"})").find("materials.m.normal_map"),
            std::string::npos);
  EXPECT_NE(
      errorOf(R"({"type": "phong", "bump_map": {"image": "checker.png", "gain": 2}})").find("gain"),
      std::string::npos);
  EXPECT_NE(errorOf(R"({"type": "phong", "bump_map": {"image": "n.png", "scale": "big"}})")
                .find("materials.m.bump_map.scale"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"type": "phong", "normal_map": {"scale": 1}})").find("image"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"type": "phong", "normal_map": {"image": "no-such.png"}})")
                .find("materials.m.normal_map.image"),
            std::string::npos);
}

// A one-triangle glTF with NORMAL +z, TEXCOORD_0, TANGENT (1, 0, 0, w) and a normal texture of
// scale 0.5.
std::string gltfTriangleWithTangents(float w) {
  using nlohmann::json;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uvs[6] = {0, 1, 1, 1, 0, 0};
  const float tangents[12] = {1, 0, 0, w, 1, 0, 0, w, 1, 0, 0, w};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(normals), sizeof normals);
  buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
  buffer.append(reinterpret_cast<const char*>(tangents), sizeof tangents);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2,
                                               "TANGENT": 3}, "material": 0}]}],
    "materials": [{"normalTexture": {"index": 0, "scale": 0.5}}],
    "textures": [{"source": 0}], "images": [{"uri": "flat_normal.png"}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
      {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 24},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 48}],
    "buffers": [{"byteLength": 144, "uri": "data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

TEST(NormalMaps, GltfTangentsAreReadWithTheirBitangentSign) {
  writeConstantImage("flat_normal.png", encoded(0, 0, 1));
  for (const float w : {1.0f, -1.0f}) {
    const std::string path = test::writeTemp("tangents.gltf", gltfTriangleWithTangents(w));
    const MeshFile file = loadMeshFile(path);
    ASSERT_EQ(file.parts.size(), 1u);
    const TriangleMesh& m = file.parts[0];
    ASSERT_EQ(m.tangents.size(), 3u);  // per corner
    for (const auto& t : m.tangents) {
      EXPECT_NEAR(t.direction.x, 1, 1e-6);
      EXPECT_EQ(t.sign, w);  // w's sign survives Assimp's bitangent = normal × xyz · w
    }
    // normalTexture with its scale, read as a normal map.
    const auto& maps = file.materials[0].surface.normalMaps;
    ASSERT_TRUE(maps && maps->normal.image);
    EXPECT_EQ(maps->normal.scale, 0.5f);
  }
}

TEST(NormalMaps, MtlNormAndBumpWithBmBecomeNormalAndBumpMaps) {
  writeConstantImage("mtl_n.png", encoded(0, 0, 1));
  writeConstantImage("mtl_h.png", {0.5f, 0.5f, 0.5f});
  test::writeTemp("bumped.mtl", "newmtl b\nKd 1 1 1\nnorm mtl_n.png\nbump -bm 0.25 mtl_h.png\n");
  const std::string obj =
      test::writeTemp("bumped.obj",
                      "mtllib bumped.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                      "usemtl b\nf 1/1 2/2 3/3\n");
  const MeshFile file = loadMeshFile(obj);
  const auto& maps = file.materials[0].surface.normalMaps;
  ASSERT_TRUE(maps);
  ASSERT_TRUE(maps->normal.image);
  EXPECT_NE(maps->normal.image->path().find("mtl_n.png"), std::string::npos);
  ASSERT_TRUE(maps->bump.image);
  EXPECT_NE(maps->bump.image->path().find("mtl_h.png"), std::string::npos);
  EXPECT_EQ(maps->bump.scale, 0.25f);  // -bm
  // map_Bump, the other spelling, reaches the bump map too.
  test::writeTemp("bumped2.mtl", "newmtl b\nKd 1 1 1\nmap_Bump -bm 2 mtl_h.png\n");
  const std::string obj2 =
      test::writeTemp("bumped2.obj",
                      "mtllib bumped2.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                      "usemtl b\nf 1/1 2/2 3/3\n");
  const std::shared_ptr<const ShadingMaps> maps2 =
      loadMeshFile(obj2).materials[0].surface.normalMaps;
  ASSERT_TRUE(maps2 && maps2->bump.image);
  EXPECT_EQ(maps2->bump.scale, 2.0f);
}

TEST(NormalMaps, AMeshUnderASceneNormalMapGetsGeneratedTangents) {
  // Inline mesh with (u, v) along (+x, +y): MikkTSpace's tangent is +x at every corner; the
  // same mesh under a material without a normal map carries none.
  writeConstantImage("scene_n.png", encoded(0, 0, 1));
  const auto meshScene = [](const std::string& maps) {
    return R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "phong")" +
           maps + R"(}},
      "objects": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]],
                   "indices": [[0,1,2]], "uvs": [[0,0],[1,0],[0,1]], "material": "m"}]})";
  };
  const std::string mapped = meshScene(R"(, "normal_map": {"image": "scene_n.png"})");
  const Scene s =
      loadSceneText(mapped, test::writeTemp("gen.json", mapped), test::tempDir().string());
  ASSERT_EQ(s.meshes[0].tangents.size(), 3u);
  for (const auto& t : s.meshes[0].tangents) EXPECT_NEAR(t.direction.x, 1, 1e-6);
  EXPECT_TRUE(s.features.normalMaps);
  const Scene plain = loadSceneText(meshScene(""), "plain.json", test::tempDir().string());
  EXPECT_TRUE(plain.meshes[0].tangents.empty());
  EXPECT_FALSE(plain.features.normalMaps);
}

}  // namespace
}  // namespace glint
