// Assimp's own broken files (Debian's assimp-testmodels: invalid/ and the deliberately broken
// glTF 2 models) as a scene's mesh: `glint render` must give an image (exit 0) or a clean error
// naming the file (exit 2) within 20 s and 4 GB of address space; never a signal or a hang.
// invalid/OutOfMemory.off once hung the loader until memory ran out.
#include <gtest/gtest.h>

#include <filesystem>

#include "bounded_render.h"
#include "film/exr_output.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

// Renders a 4×4 frame of a scene holding `mesh`, bounded in time and memory.
test::BoundedOutcome renderMesh(const fs::path& mesh) {
  const std::string scene = test::writeTemp(
      "assimp-model.json",
      R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "materials": {"m": {"type": "phong"}},
          "objects": [{"type": "mesh", "file": ")" +
          mesh.string() + R"(", "material": "m"}]})");
  return test::renderBounded(scene, 4);
}

void expectImageOrCleanError(const fs::path& mesh) {
  const test::BoundedOutcome o = renderMesh(mesh);
  EXPECT_TRUE(o.status == 0 || o.status == 2) << mesh << ": exit " << o.status << "\n" << o.output;
  if (o.status == 2) {
    EXPECT_NE(o.output.find(mesh.string()), std::string::npos) << mesh << ": " << o.output;
  }
}

TEST(AssimpModels, EveryInvalidFileGivesAnImageOrACleanError) {
  if (!fs::is_directory(kModels / "invalid"))
    GTEST_SKIP() << "assimp-testmodels is not installed (" << kModels / "invalid"
                 << " is missing); tools/lib.sh installs it";
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kModels / "invalid")) {
    expectImageOrCleanError(entry.path());
    ++files;
  }
  EXPECT_GE(files, 15u) << "assimp-testmodels 5.2.5 has 15 files in invalid/";
}

TEST(AssimpModels, EveryBrokenGltfGivesAnImageOrACleanError) {
  if (!fs::is_directory(kModels / "glTF2"))
    GTEST_SKIP() << "assimp-testmodels is not installed; tools/lib.sh installs it";
  for (const char* mesh :
       {"IndexOutOfRange/IndexOutOfRange.gltf", "IndexOutOfRange/AllIndicesOutOfRange.gltf",
        "MissingBin/BoxTextured.gltf", "RecursiveNodes/RecursiveNodes.gltf",
        "SchemaFailures/sceneWrongType.gltf", "TestNoRootNode/NoScene.gltf",
        "TestNoRootNode/SceneWithoutNodes.gltf", "wrongTypes/badArray.gltf",
        "wrongTypes/badNumber.gltf", "wrongTypes/badUint.gltf", "IncorrectVertexArrays/Cube.gltf",
        "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "issue_3269/texcoord_crash.gltf"})
    expectImageOrCleanError(kModels / "glTF2" / mesh);
}

TEST(AssimpModels, OutOfMemoryOffIsRefusedByItsFormat) {
  if (!fs::exists(kModels / "invalid/OutOfMemory.off"))
    GTEST_SKIP() << "assimp-testmodels is not installed; tools/lib.sh installs it";
  const test::BoundedOutcome o = renderMesh(kModels / "invalid/OutOfMemory.off");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("Glint reads OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb), Collada "
                          "(.dae), FBX (.fbx), 3DS (.3ds), AC3D (.ac), STL (.stl), Milkshape 3D "
                          "(.ms3d) and X3D (.x3d)"),
            std::string::npos)
      << o.output;
}

// The share of a frame's pixels the asset covers (alpha > 0 under --transparent-background)
// and the mean brightness of those pixels.
struct Coverage {
  double share = 0, meanLuminance = 0;
};
Coverage coverageOf(const std::string& exr) {
  const Image img = readImage(exr);
  Coverage c;
  size_t covered = 0;
  for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p) {
    const float* px = &img.pixels[p * size_t(img.channels)];
    if (px[3] <= 0) continue;
    ++covered;
    c.meanLuminance += (px[0] + px[1] + px[2]) / 3;
  }
  c.share = double(covered) / double(img.width * img.height);
  c.meanLuminance /= double(std::max<size_t>(covered, 1));
  return c;
}

TEST(AssimpModels, AMeshFileRendersAsASceneFramedAndLit) {
  // `glint render asset.obj`: the default camera frames the bounding sphere (it fills the
  // frame's height with a tenth to spare), so the asset is seen whole and not lost in a corner,
  // and the default light and ambient light show it. A written quad first (always here): the
  // unit square seen from the front, right and above covers a good part of the frame.
  const std::string quad =
      test::writeTemp("framed.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  const auto render = [](const std::string& mesh, const std::string& out) {
    return test::runGlint("render " + mesh + " --quiet --spp 1 --width 64 --height 48 " +
                          "--transparent-background -o " + out);
  };
  const std::string quadOut = (test::tempDir() / "framed.exr").string();
  ASSERT_EQ(render(quad, quadOut).exitCode, 0);
  const Coverage q = coverageOf(quadOut);
  // The square's circumscribed sphere (radius √2) spans 1/1.1 of the frame's height: the camera
  // stands d = 1.1·√2/sin 20° = 4.55 away, where the 4:3 frame is 4.41 × 3.31 = 14.6 units²,
  // along (0.5, 0.4, 1), at cos 0.84 to the square's normal. Its 4 units² seen foreshortened,
  // 3.37, cover about 0.23 of the frame; ±0.03 for perspective and 64 × 48 pixels' edges
  // (measured 0.237).
  EXPECT_NEAR(q.share, 0.23, 0.03);
  EXPECT_GT(q.meanLuminance, 0.1);

  const fs::path spider = kModels / "OBJ/spider.obj";
  if (!fs::exists(spider)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const std::string spiderOut = (test::tempDir() / "spider.exr").string();
  const auto r = render(spider.string(), spiderOut);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Coverage c = coverageOf(spiderOut);
  // A thin-legged spider covers less of its bounding sphere than a square: seen, not filling.
  EXPECT_GT(c.share, 0.03);
  EXPECT_LT(c.share, 0.6);
  // Lit, in its own colours: its JPEG maps are dark browns and greys (linear albedo mostly
  // 0.05-0.3), which the default light brings to a mean of about 0.04 over the covered pixels
  // (measured 0.043), well above what the ambient light alone (0.1 × albedo) could give.
  EXPECT_GT(c.meanLuminance, 0.025);
}

TEST(AssimpModels, ClosedModelsAreCsgOperandsAndOpenOnesAreRefused) {
  // Assimp's cube.ply ([0, 1]³, quads), box.obj ([−0.5, 0.5]³) and cube_uv.ply ([−1, 1]³, its
  // vertices split per face by Blender's export) placed as the unit cube around z = −5, minus a
  // sphere of radius 0.3 there: a ray from the origin down −z is inside the solid over
  // [4.5, 4.7] and [5.3, 5.5]. The Wuson model has holes, and CSG refuses it, naming an edge.
  if (!fs::exists(kModels / "PLY/cube.ply")) GTEST_SKIP() << "assimp-testmodels is not installed";
  const auto solid = [](const std::string& file, const std::string& transform) {
    return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
      "materials": {"m": {"type": "phong"}},
      "objects": [{"type": "csg", "op": "difference", "material": "m", "operands": [
        {"type": "mesh", "file": ")" +
                               (kModels / file).string() + R"(", "transform": )" + transform + R"(},
        {"type": "sphere", "center": [0,0,-5], "radius": 0.3}]}]})");
  };
  for (const auto& [file, transform] :
       {std::pair{"PLY/cube.ply", R"({"translate": [-0.5,-0.5,-5.5]})"},
        std::pair{"OBJ/box.obj", R"({"translate": [0,0,-5]})"},
        std::pair{"PLY/cube_uv.ply", R"({"scale": [0.5,0.5,0.5], "translate": [0,0,-5]})"}}) {
    SCOPED_TRACE(file);
    const Scene s = solid(file, transform);
    const std::vector<CsgSpan> spans = s.csgs[0].spans({{0, 0, 0}, {0, 0, -1}});
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].in.t, 4.5, 1e-5);
    EXPECT_NEAR(spans[0].out.t, 4.7, 1e-5);
    EXPECT_NEAR(spans[1].in.t, 5.3, 1e-5);
    EXPECT_NEAR(spans[1].out.t, 5.5, 1e-5);
  }
  try {
    solid("OBJ/WusonOBJ.obj", R"({"translate": [0,0,-5]})");
    ADD_FAILURE() << "an open mesh was accepted as a CSG operand";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a closed surface: the edge from"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace glint
