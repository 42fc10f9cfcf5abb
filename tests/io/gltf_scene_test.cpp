// glTF 2.0 files as whole scenes (io/gltf_scene.h, app/scene_source.h): their cameras, their
// KHR_lights_punctual lights and their materials, placed by the node tree.
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "accel/accelerator.h"
#include "app/scene_source.h"
#include "camera/camera.h"
#include "io/gltf_scene.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// A 2 × 2 quad in the z = 0 plane facing +z, base colour (0.8, 0.2, 0.1), not metallic,
// roughness 1; a camera "front" 3 units in front of it and a camera "side" 3 units to its right
// turned to look at it edge on (a node rotation of 90° about y, under a parent that moves it);
// a white directional light of π lux shining along its node's −z.
std::string quadScene(const std::string& nodes) {
  const float positions[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
    "nodes": [)" +
         nodes + R"(],
    "cameras": [{"name": "front", "type": "perspective",
                 "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}},
                {"name": "side", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "directional", "color": [1, 1, 1], "intensity": 3.14159265358979}]}},
    "extensionsUsed": ["KHR_lights_punctual"],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1],
                   "metallicFactor": 0, "roughnessFactor": 1}}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
       "min": [-1, -1, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [{"byteLength": 60,
                 "uri": "data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

const char* kNodes = R"({"mesh": 0},
    {"camera": 0, "translation": [0, 0, 3]},
    {"translation": [1, 0, 0], "children": [4]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"camera": 1, "translation": [2, 0, 0], "rotation": [0, 0.70710678, 0, 0.70710678]})";

// The centre pixel's RGB as the file's camera `camera` (empty: its first) sees it.
std::array<double, 3> centre(const std::string& file, const std::string& camera) {
  Scene scene = loadSceneOrDefault(file, std::nullopt, camera);
  scene.render.width = scene.render.height = 33;  // odd: a pixel sits on the axis
  scene.render.spp = 1;
  scene.render.sampler = SamplerKind::Regular;
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  const Film film = renderScene(scene, *accel, opt).film;
  const float* px = film.pixel(16, 16);
  return {px[0], px[1], px[2]};
}

TEST(GltfScene, CamerasAndLightsAreReadAndPlacedByTheNodeTree) {
  const std::string file = test::writeTemp("quad_scene.gltf", quadScene(kNodes));
  const FileSceneInfo info = readGltfSceneInfo(file);
  ASSERT_EQ(info.cameras.size(), 2u);
  EXPECT_EQ(info.cameras[0].name, "front");
  EXPECT_NEAR(info.cameras[0].eye.z, 3, 1e-12);
  EXPECT_NEAR(info.cameras[0].yfovDegrees, 0.5 * 180 / M_PI, 1e-9);
  EXPECT_EQ(info.cameras[0].aspectRatio, 1.5);
  // "side": translated by its parent (1, 0, 0) and itself (2, 0, 0), turned 90° about +y, so
  // its −z looks along −x.
  EXPECT_NEAR(info.cameras[1].eye.x, 3, 1e-9);
  EXPECT_NEAR(info.cameras[1].lookAt.x - info.cameras[1].eye.x, -1, 1e-6);
  ASSERT_EQ(info.lights.size(), 1u);
  EXPECT_EQ(info.lights[0].type, FileLight::Type::Directional);
  EXPECT_NEAR(info.lights[0].direction.z, -1, 1e-12);
}

TEST(GltfScene, RendersWithItsOwnCameraLightAndBaseColour) {
  const std::string file = test::writeTemp("quad_render.gltf", quadScene(kNodes));
  // Seen head on by "front" (the first camera), lit head on by π lux, which Glint takes as
  // intensity 1: k_d = base colour, plus the dielectric highlight k_s = 0.04 with exponent 1
  // (roughness 1) at n·h = 1, plus the ambient term k_a·0.1 (a glTF material's k_a is its
  // diffuse colour, which its occlusion texture would darken). The centre pixel's view is
  // 0.2 mrad off the axis: n·h differs from 1 by under 1e-7.
  const std::array<double, 3> px = centre(file, "");
  EXPECT_NEAR(px[0], 0.8 + 0.04 + 0.08, 1e-5);
  EXPECT_NEAR(px[1], 0.2 + 0.04 + 0.02, 1e-5);
  EXPECT_NEAR(px[2], 0.1 + 0.04 + 0.01, 1e-5);
  // "side" sees the quad edge on: its centre pixel's ray runs in the quad's plane and shows
  // the background (the default scene's, 0.18, 0.18, 0.2).
  const std::array<double, 3> side = centre(file, "side");
  EXPECT_NEAR(side[0], 0.18, 1e-6);
  EXPECT_NEAR(side[2], 0.2, 1e-6);
}

TEST(GltfScene, AnUnknownCameraNamesTheCamerasThereAre) {
  const std::string file = test::writeTemp("quad_names.gltf", quadScene(kNodes));
  try {
    loadSceneOrDefault(file, std::nullopt, "top");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("\"front\", \"side\""), std::string::npos) << e.what();
  }
}

TEST(GltfScene, ACameraPlacedByTwoNodesIsChosenByEither) {
  // Camera "front" placed again by a child of the mesh's node, 5 units out (visited first): the
  // cameras were listed as "front", "front", "side", and the second could not be chosen.
  std::string nodes = kNodes;
  const std::string meshNode = R"({"mesh": 0})";
  nodes.replace(nodes.find(meshNode), meshNode.size(), R"({"mesh": 0, "children": [5]})");
  nodes += R"(, {"camera": 0, "translation": [0, 0, 5]})";
  const std::string file = test::writeTemp("quad_twice.gltf", quadScene(nodes));
  const FileSceneInfo info = readGltfSceneInfo(file);
  ASSERT_EQ(info.cameras.size(), 3u);
  EXPECT_EQ(info.cameras[0].name, "front");
  EXPECT_NEAR(info.cameras[0].eye.z, 5, 1e-12);
  EXPECT_EQ(info.cameras[1].name, "front (nodes[1])");
  EXPECT_NEAR(info.cameras[1].eye.z, 3, 1e-12);
  EXPECT_EQ(info.cameras[2].name, "side");
  EXPECT_EQ(loadSceneOrDefault(file, std::nullopt, "front (nodes[1])").cameraDesc.eye.z, 3.0f);
  EXPECT_EQ(loadSceneOrDefault(file, std::nullopt, "front").cameraDesc.eye.z, 5.0f);
  try {
    loadSceneOrDefault(file, std::nullopt, "top");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("\"front\", \"front (nodes[1])\", \"side\""),
              std::string::npos)
        << e.what();
  }
}

// quadScene with its one light replaced by `light`.
std::string quadWithLight(const std::string& light) {
  std::string text = quadScene(kNodes);
  const std::string directional =
      R"({"type": "directional", "color": [1, 1, 1], "intensity": 3.14159265358979})";
  text.replace(text.find(directional), directional.size(), light);
  return text;
}

TEST(GltfScene, SpotLightsKeepTheirCones) {
  // Light node 3 sits at the origin facing −z (no rotation); cones of 0.2 and 0.5 radians.
  const std::string file = test::writeTemp(
      "quad_spot.gltf",
      quadWithLight(R"({"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.2,
                                                                 "outerConeAngle": 0.5}})"));
  const Scene scene = loadSceneOrDefault(file, std::nullopt, "");
  ASSERT_EQ(scene.lights.size(), 1u);
  const auto* spot = std::get_if<PointLight>(&scene.lights[0]);
  ASSERT_NE(spot, nullptr);
  ASSERT_TRUE(spot->isSpot());
  EXPECT_NEAR(spot->spotAxis.z, -1, 1e-6);
  EXPECT_NEAR(spot->cosInner, std::cos(0.2), 1e-6);
  EXPECT_NEAR(spot->cosOuter, std::cos(0.5), 1e-6);
  EXPECT_NEAR(spot->intensity.r, 2 / M_PI, 1e-6);  // candela over π (scene_source.cpp)
  // The specification wants 0 ≤ inner < outer ≤ π/2.
  const std::string bad = test::writeTemp(
      "quad_bad_spot.gltf",
      quadWithLight(R"({"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.5}})"));
  try {
    readGltfSceneInfo(bad);
    FAIL() << "no error";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find("innerConeAngle < outerConeAngle"), std::string::npos)
        << e.what();
  }
}

TEST(GltfScene, ACyclicNodeTreeIsRefused) {
  // Node 0 lists node 4 as its child, and 4 lists 0: an endless recursion in a naive reader.
  const std::string nodes = R"({"mesh": 0, "children": [4]},
    {"camera": 0, "translation": [0, 0, 3]}, {}, {},
    {"children": [0]})";
  const std::string file = test::writeTemp("quad_cycle.gltf", quadScene(nodes));
  try {
    readGltfSceneInfo(file);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes[0] is its own ancestor"), std::string::npos)
        << e.what();
  }
}

TEST(GltfScene, ANodeTreeThatExpandsPastTheLimitIsRefusedBeforeItsCamerasAreRead) {
  // 41 nodes, each listing the next twice: 2^41 paths, which the camera and light reader walked
  // one by one (it hung) once it no longer ran the subset's checks. It is refused as the mesh
  // reader refuses it.
  std::string nodes = R"({"mesh": 0, "children": [1, 1]})";
  for (int i = 1; i < 41; ++i)
    nodes += ", {\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}";
  nodes += ", {}";
  const std::string file = test::writeTemp("quad_dag.gltf", quadScene(nodes));
  try {
    readGltfSceneInfo(file);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("node copies"), std::string::npos) << e.what();
  }
}

// glTF's orthographic projection maps [−xmag, xmag] × [−ymag, ymag] onto the image (glTF 2.0,
// "Projection Matrices"): xmag 1.5, ymag 1 showed ±1.33 across, the 4:3 default's width at
// ymag's height.
TEST(GltfScene, AnOrthographicCameraSpansXmagAndYmag) {
  std::string text = quadScene(kNodes);
  const std::string front = R"({"name": "front", "type": "perspective",
                 "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}})";
  ASSERT_NE(text.find(front), std::string::npos);
  text.replace(text.find(front), front.size(),
               R"({"name": "front", "type": "orthographic",
                   "orthographic": {"xmag": 1.5, "ymag": 1, "znear": 0.1, "zfar": 100}})");
  const std::string file = test::writeTemp("quad_ortho.gltf", text);
  const Scene scene = loadSceneOrDefault(file, std::nullopt, "front");
  // The image takes the camera's aspect xmag / ymag at the default height: 480 · 1.5.
  EXPECT_EQ(scene.render.height, 480);
  EXPECT_EQ(scene.render.width, 720);
  // The camera sits at (0, 0, 3) looking down −z, +y up: the film's top-left corner is
  // (−xmag, +ymag) across the image plane, its bottom-right (+xmag, −ymag), rays along −z.
  const Camera camera(scene.cameraDesc, scene.render.width, scene.render.height);
  const Ray topLeft = camera.generateRay(0, 0);
  EXPECT_NEAR(topLeft.o.x, -1.5, 1e-6);
  EXPECT_NEAR(topLeft.o.y, 1, 1e-6);
  EXPECT_NEAR(topLeft.o.z, 3, 1e-6);
  EXPECT_NEAR(topLeft.d.z, -1, 1e-6);
  // The centre of pixel (540, 120) of 720 × 480: u = −1.5 + 3 · 540.5 / 720 = 0.752083…,
  // v = 1 − 2 · 120.5 / 480 = 0.497916….
  const Ray inside = camera.generateRay(540.5f, 120.5f);
  EXPECT_NEAR(inside.o.x, -1.5 + 3 * 540.5 / 720, 1e-5);
  EXPECT_NEAR(inside.o.y, 1 - 2 * 120.5 / 480, 1e-5);
  // Another image size (--width 640 --height 480) keeps the view glTF's projection gives,
  // ±1.5 × ±1, with pixels 1.5 / (4/3) = 1.125 times as wide as tall (docs/scene-format.md).
  const Camera narrower(scene.cameraDesc, 640, 480);
  EXPECT_NEAR(narrower.generateRay(640, 480).o.x, 1.5, 1e-6);
  EXPECT_NEAR(narrower.generateRay(640, 480).o.y, -1, 1e-6);
}

TEST(GltfScene, AnOrthographicCameraNeedsBothMagnifications) {
  std::string text = quadScene(kNodes);
  const std::string front = R"({"name": "front", "type": "perspective",
                 "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}})";
  text.replace(text.find(front), front.size(),
               R"({"type": "orthographic", "orthographic": {"ymag": 1, "znear": 0, "zfar": 9}})");
  const std::string file = test::writeTemp("quad_ortho_no_xmag.gltf", text);
  try {
    readGltfSceneInfo(file);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "glTF " + file + ": cameras[0].orthographic.xmag must be positive");
  }
}

TEST(GltfScene, ACameraThatCannotMakeAnImageIsRefusedByName) {
  // An aspect ratio of 1e9 made the width int(480e9), undefined, and the frame came out 1 × 480;
  // 100 made it 48000, past the 32768 a width may be. An orthographic view past ±1e18 failed at
  // render, exit 1, naming no file or camera. Each is now exit 2, naming the file and camera.
  const std::string front = R"({"name": "front", "type": "perspective",
                 "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}})";
  const auto refusal = [&](const std::string& name, const std::string& camera) {
    std::string text = quadScene(kNodes);
    text.replace(text.find(front), front.size(), camera);
    const std::string file = test::writeTemp(name, text);
    try {
      loadSceneOrDefault(file, std::nullopt, "front");
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  const std::string wide = refusal("wide.gltf", R"({"name": "front", "type": "perspective",
      "perspective": {"yfov": 0.5, "aspectRatio": 1e9, "znear": 0.1}})");
  EXPECT_NE(wide.find("wide.gltf: camera \"front\": its aspect ratio 1e+09 makes an image "
                      "4.8e+11 pixels wide at height 480"),
            std::string::npos)
      << wide;
  EXPECT_NE(refusal("hundred.gltf", R"({"name": "front", "type": "perspective",
      "perspective": {"yfov": 0.5, "aspectRatio": 100, "znear": 0.1}})")
                .find("makes an image 48000 pixels wide"),
            std::string::npos);
  const std::string far = refusal("far.gltf", R"({"name": "front", "type": "orthographic",
      "orthographic": {"xmag": 1e19, "ymag": 1e19, "znear": 0.1, "zfar": 100}})");
  EXPECT_NE(far.find("far.gltf: camera \"front\": the image window"), std::string::npos) << far;
  // At the limits' edge it loads: 68.2666… rounds to a width of 32768.
  EXPECT_EQ(refusal("edge.gltf", R"({"name": "front", "type": "perspective",
      "perspective": {"yfov": 0.5, "aspectRatio": 68.2666, "znear": 0.1}})"),
            "(loaded)");
}

}  // namespace
}  // namespace glint
