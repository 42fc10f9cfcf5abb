// Mesh files of the formats Assimp reads for Glint (io/scene_formats.h) as `glint render`'s
// scene: Collada's duck.dae renders with its texture's colours and its own camera and light, a
// Collada camera is the scene's (and `--camera` picks it by name), and a truncated or garbled
// file of each format ends in a clean error naming it (exit 2) within 20 s and 4 GB of address
// space.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/scene_source.h"
#include "bounded_render.h"
#include "collada_util.h"
#include "core/error.h"
#include "film/exr_output.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

// `glint render SCENE` of an 8×8 frame, bounded in time and memory.
test::BoundedOutcome renderBounded(const std::string& scene, const std::string& args = "") {
  return test::renderBounded(scene, 8, args);
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The mean colour of the pixels the asset covers (alpha 1 under --transparent-background).
Rgb meanCoveredColour(const std::string& exr) {
  const Image img = readImage(exr);
  double sum[3] = {0, 0, 0};
  size_t covered = 0;
  for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p) {
    const float* px = &img.pixels[p * size_t(img.channels)];
    if (px[3] < 0.999f) continue;
    ++covered;
    for (int c = 0; c < 3; ++c) sum[c] += px[c];
  }
  EXPECT_GT(covered, 50u) << exr << ": the asset should cover a good part of the frame";
  const double n = double(std::max<size_t>(covered, 1));
  return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n)};
}

TEST(AssimpFormats, DuckRendersWithItsTextureColours) {
  const fs::path duck = kModels / "Collada/duck.dae";
  if (!fs::exists(duck))
    GTEST_SKIP() << "assimp-testmodels is not installed (" << duck
                 << " is missing): Collada textures are untested here; tools/lib.sh installs it";
  const std::string exr = (test::tempDir() / "duck.exr").string();
  const auto r = test::runGlint("render " + duck.string() +
                                " --width 72 --height 48 --spp 4 --transparent-background "
                                "--quiet -o " +
                                exr);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // duckCM.tga is a yellow duck with an orange beak: red and green well above blue, green a
  // little below red. Untextured (its white diffuse colour) the same pixels are grey, blue as
  // high as red (below).
  const Rgb duckColour = meanCoveredColour(exr);
  EXPECT_GT(duckColour.g, 0.6 * duckColour.r) << duckColour.r << " " << duckColour.g;
  EXPECT_LT(duckColour.g, 1.0 * duckColour.r) << duckColour.r << " " << duckColour.g;
  EXPECT_LT(duckColour.b, 0.3 * duckColour.r) << duckColour.r << " " << duckColour.b;
  // Without duckCM.tga beside it the texture is left out, with a warning, and the duck is
  // its diffuse colour, white.
  const fs::path bare = test::tempDir() / "bare-duck";
  fs::create_directories(bare);
  fs::copy_file(duck, bare / "duck.dae", fs::copy_options::overwrite_existing);
  const std::string bareExr = (test::tempDir() / "bare-duck.exr").string();
  const auto b =
      test::runGlint("render " + (bare / "duck.dae").string() +
                     " --width 72 --height 48 --spp 4 --transparent-background -o " + bareExr);
  ASSERT_EQ(b.exitCode, 0) << b.output;
  EXPECT_NE(b.output.find("texture left out"), std::string::npos) << b.output;
  const Rgb grey = meanCoveredColour(bareExr);
  EXPECT_NEAR(grey.b, grey.r, 0.05 * grey.r);
}

TEST(AssimpFormats, AColladaCameraIsTheScenes) {
  const std::string file = test::writeTemp("viewed.dae", test::colladaDocument());
  const Scene s = loadSceneOrDefault(file);
  // colladaDocument's camera: at z = 5 looking down −z, yfov 30°, aspect 2 (the image's width
  // follows it at the default height).
  EXPECT_NEAR(s.cameraDesc.eye.z, 5, 1e-6);
  EXPECT_NEAR(s.cameraDesc.lookAt.z, 4, 1e-6);
  EXPECT_NEAR(s.cameraDesc.vfovDegrees, 30, 1e-3);
  EXPECT_EQ(s.render.width, 2 * s.render.height);
  // By name, and a wrong name lists the file's cameras.
  EXPECT_NEAR(loadSceneOrDefault(file, std::nullopt, "view").cameraDesc.eye.z, 5, 1e-6);
  try {
    loadSceneOrDefault(file, std::nullopt, "top");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("has the cameras \"view\""), std::string::npos)
        << e.what();
  }
}

TEST(AssimpFormats, TruncatedAndGarbledFilesEndInACleanError) {
  std::vector<std::pair<std::string, std::string>> files = {
      {"tri.dae", test::colladaDocument()},
      {"tri.stl",
       "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
       "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"},
      {"tri.ac",
       "AC3Db\nMATERIAL \"m\" rgb 1 0 0 amb 0 0 0 emis 0 0 0 spec 0 0 0 shi 1 trans 0\n"
       "OBJECT world\nkids 1\nOBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\n"
       "SURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n"},
      {"tri.x3d",
       "<?xml version=\"1.0\"?>\n<X3D><Scene><Shape><IndexedFaceSet coordIndex=\"0 1 "
       "2 -1\"><Coordinate point=\"0 0 0 1 0 0 0 1 0\"/></IndexedFaceSet></Shape>"
       "</Scene></X3D>\n"}};
  for (const char* name : {"FBX/box.fbx", "3DS/cube_with_diffuse_texture.3DS",
                           "MS3D/twospheres.ms3d", "STL/Spider_binary.stl"}) {
    if (fs::exists(kModels / name))
      files.emplace_back(fs::path(name).filename().string(), readBytes(kModels / name));
    else
      ADD_FAILURE() << "assimp-testmodels is not installed (" << kModels / name
                    << " is missing): this format's truncation is untested; tools/lib.sh "
                       "installs it";
  }
  // duck.dae with one byte of an index list turned to 0x80 looped forever in Assimp's reader.
  if (fs::exists(kModels / "Collada/duck.dae")) {
    std::string duck = readBytes(kModels / "Collada/duck.dae");
    duck[duck.find("<p>") + 10] = '\x80';
    files.emplace_back("hang.dae", duck);
  }
  for (const auto& [name, bytes] : files) {
    for (const double keep : {0.3, 0.7}) {
      const std::string path = test::writeTemp(
          "cut" + std::to_string(int(keep * 10)) + "-" + name,
          name == "hang.dae" ? bytes : bytes.substr(0, size_t(keep * double(bytes.size()))));
      const test::BoundedOutcome o = renderBounded(path);
      EXPECT_EQ(o.status, 2) << path << "\n" << o.output;
      EXPECT_NE(o.output.find(path), std::string::npos) << o.output;
    }
  }
}

}  // namespace
}  // namespace glint
