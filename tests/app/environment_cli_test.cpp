// The environment light from the command line: `--environment` for a mesh-file scene (CLI.md),
// refused for a scene file, and the bundled scenes/sky.json rendered to the same bytes for any
// thread count, tile size and backend.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include "test_util.h"

namespace glint {
namespace {

using test::runGlint;

std::vector<float> pixelsOf(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  return pixels;
}

const std::string kSky = std::string(GLINT_SCENES_DIR) + "/sky.json";
const std::string kSkyImage = std::string(GLINT_SCENES_DIR) + "/sky.hdr";
const std::string kMesh = std::string(GLINT_SCENES_DIR) + "/meshes/wuson.obj";

TEST(EnvironmentCli, SkySceneIsTheSameForAnyThreadCountTileSizeAndBackend) {
  // The backends share every intersection routine (spheres and quads) and differ only in
  // traversal; the sampler's numbers never depend on a thread: the same bytes every way.
  const auto out = [](const std::string& n) { return (test::tempDir() / (n + ".exr")).string(); };
  const std::string common = "render " + kSky + " --quiet --width 48 --height 27 --spp 2 -o ";
  ASSERT_EQ(runGlint(common + out("sky_a") + " --threads 1 --tile-size 64").exitCode, 0);
  ASSERT_EQ(runGlint(common + out("sky_b") + " --threads 2 --tile-size 8 --accel bvh").exitCode, 0);
  ASSERT_EQ(runGlint(common + out("sky_c") + " --threads 2 --accel kdtree").exitCode, 0);
  const std::vector<float> a = pixelsOf(out("sky_a"));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(pixelsOf(out("sky_b")), a);
  EXPECT_EQ(pixelsOf(out("sky_c")), a);
}

TEST(EnvironmentCli, LightsAMeshFileAndStatsSayItIsUsed) {
  const std::string out = (test::tempDir() / "wuson_sky.exr").string();
  const auto r = runGlint("render " + kMesh + " --environment " + kSkyImage +
                          " --width 32 --height 24 --spp 1 --stats -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Used, and the default directional light it replaces is not there.
  EXPECT_NE(r.output.find("features used    environment_light"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("directional_lights"), std::string::npos);  // listed as left out
  const auto plain = runGlint("render " + kMesh + " --width 32 --height 24 --spp 1 --stats -o " +
                              (test::tempDir() / "wuson_plain.exr").string());
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  EXPECT_NE(plain.output.find("environment_light"), std::string::npos);  // left out
  EXPECT_EQ(plain.output.find("features used    environment_light"), std::string::npos);
}

TEST(EnvironmentCli, RefusedForASceneFileAndForAMissingImage) {
  const std::string out = (test::tempDir() / "refused_sky.exr").string();
  const auto scene = runGlint("render " + kSky + " --environment " + kSkyImage + " -o " + out);
  EXPECT_EQ(scene.exitCode, 2);
  EXPECT_NE(scene.output.find("--environment " + kSkyImage +
                              ": adds an environment light to a mesh-file scene; " + kSky +
                              " declares its lights itself"),
            std::string::npos)
      << scene.output;
  const auto missing =
      runGlint("render " + kMesh + " --environment /nonexistent/sky.exr -o " + out);
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.output.find("--environment /nonexistent/sky.exr: "), std::string::npos)
      << missing.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(EnvironmentCli, ErrorsOfAMeshFileSceneNameWhatTheUserGave) {
  // The scene Glint writes for a mesh file has no lines the user knows: an image that cannot
  // be read was reported as "wuson.obj:1: lights[1].image: ...", a mesh file as
  // "m.gltf:1: objects[0].file: ...".
  const std::string out = (test::tempDir() / "named_sky.exr").string();
  const std::string bad = test::writeTemp("bad-sky.hdr", "#?RADIANCE\n");
  const auto image = runGlint("render " + kMesh + " --environment " + bad + " -o " + out);
  EXPECT_EQ(image.exitCode, 2);
  EXPECT_NE(image.output.find("error: --environment " + bad + ": cannot read texture " + bad),
            std::string::npos)
      << image.output;
  const std::string mesh = test::writeTemp("cut.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  const auto cut = runGlint("render " + mesh + " -o " + out);
  EXPECT_EQ(cut.exitCode, 2);
  EXPECT_NE(cut.output.find("error: " + mesh + ": "), std::string::npos) << cut.output;
  EXPECT_EQ(cut.output.find("objects[0]"), std::string::npos) << cut.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace glint
