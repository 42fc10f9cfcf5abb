// The command says what it will do and its outputs are safe (issue 41): time-limited renders
// announce the limit, options of several values name what they got, scene formats Glint does
// not read are named with those it does, two options never name one file, and every refusal of
// an input or output comes before any work, with exit 2 (CLI.md: bad usage).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

const std::string kScene = std::string(GLINT_SCENES_DIR) + "/soft_shadows.json";

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CommandPromises, ATimeLimitedRenderAnnouncesItsLimit) {
  const auto r = runGlint("render " + kScene + " --width 16 --height 12 --time-limit 0.2 " +
                          "--max-spp 4096 -o " + tmp("limited.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(contains(r.output,
                       "rendering 16x12 for at most 0.2 s, up to 4096 spp (a first "
                       "pass of 8 spp always finishes) to " +
                           tmp("limited.exr")))
      << r.output;
  EXPECT_FALSE(contains(r.output, "at 16 spp")) << r.output;
}

TEST(CommandPromises, OptionsOfSeveralValuesSayWhatTheyGot) {
  const std::string out = tmp("crop-short.exr");
  const auto shortCrop = runGlint("render " + kScene + " --crop 0 10 -o " + out);
  EXPECT_EQ(shortCrop.exitCode, 2);
  EXPECT_TRUE(contains(shortCrop.output, "--crop takes 4 integers X0 X1 Y0 Y1, got 2: 0 10"))
      << shortCrop.output;
  const auto longCrop = runGlint("render " + kScene + " --crop 0 10 0 5 7 -o " + out);
  EXPECT_EQ(longCrop.exitCode, 2);
  EXPECT_TRUE(contains(longCrop.output, "got 5: 0 10 0 5 7")) << longCrop.output;
  EXPECT_FALSE(fs::exists(out));
  // -o takes one path each time: the scene after it is the scene ("-o is given 2 times").
  const auto sceneAfter =
      runGlint("render -o " + out + " " + kScene + " --quiet --width 8 --height 6 --spp 1");
  EXPECT_EQ(sceneAfter.exitCode, 0) << sceneAfter.output;
  EXPECT_TRUE(fs::exists(out));
  // validate --ray takes its nine numbers quoted or not; eight are refused by count.
  const auto ray = runGlint("validate " + kScene + " --no-brute --rays 0 --spp 0 " +
                            "--ray 0 0.5 5 0 0 -1 0 inf 0");
  EXPECT_EQ(ray.exitCode, 0) << ray.output;
  const auto shortRay = runGlint("validate " + kScene + " --ray \"0 0.5 5 0 0 -1 0 inf\"");
  EXPECT_EQ(shortRay.exitCode, 2);
  EXPECT_TRUE(contains(shortRay.output,
                       "--ray takes 9 numbers ox oy oz dx dy dz tmin tmax time, "
                       "got 8: 0 0.5 5 0 0 -1 0 inf"))
      << shortRay.output;
}

TEST(CommandPromises, ScenesOfFormatsGlintDoesNotReadAreNamedByEveryCommand) {
  // LightWave: one of Assimp's readers Glint leaves out (docs/hardening.md, "Mesh formats").
  const std::string lwo = test::writeTemp("wuson.lwo", "FORM LWO2");
  for (const std::string command : {"render", "validate", "converge", "bench", "plan", "info"}) {
    const auto r = runGlint(command + " " + lwo);
    EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, lwo + ": Glint does not read .lwo files; it reads Glint "
                                         "scenes (.json), OBJ (.obj), PLY (.ply), glTF 2.0 "
                                         "(.gltf, .glb), Collada (.dae), FBX (.fbx), 3DS (.3ds), "
                                         "AC3D (.ac), STL (.stl), Milkshape 3D (.ms3d) and X3D "
                                         "(.x3d)"))
        << command << "\n"
        << r.output;
  }
}

TEST(CommandPromises, GltfOneAndMalformedGltfAreSceneErrors) {
  // CesiumMilkTruck.gltf of assimp-testmodels gives its version as the number 1.
  const std::string one = test::writeTemp(
      "truck.gltf", R"({"asset": {"version": 1}, "nodes": {"node_1": {"meshes": ["m"]}}})");
  const auto r = runGlint("render " + one + " -o " + tmp("truck.exr"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "mesh " + one +
                                     ": glTF 1.0 is not supported; Glint reads glTF "
                                     "2.0"))
      << r.output;
  const std::string real = "/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf";
  if (fs::exists(real)) {
    const auto truck = runGlint("info " + real);
    EXPECT_EQ(truck.exitCode, 2) << truck.output;
    EXPECT_TRUE(contains(truck.output, "glTF 1.0 is not supported")) << truck.output;
  }
  // Malformed JSON exited 1, as a runtime failure, where other bad meshes exit 2.
  const std::string broken = test::writeTemp("broken.gltf", "{\"asset\": ");
  const auto b = runGlint("render " + broken + " -o " + tmp("broken.exr"));
  EXPECT_EQ(b.exitCode, 2) << b.output;
  EXPECT_TRUE(contains(b.output, "mesh " + broken + ": not glTF JSON")) << b.output;
}

TEST(CommandPromises, TwoOptionsNamingOneFileAreRefusedBeforeAnyWork) {
  struct Case {
    std::string args, says;
  };
  // The plot's format is checked first: the three converge outputs share an .svg name.
  const std::string x = tmp("same.exr"), p = tmp("same.png"), j = tmp("same.svg");
  const std::vector<Case> cases = {
      {"render " + kScene + " -o " + x + " --stats-json " + x,
       "-o " + x + " and --stats-json " + x + " name one file"},
      {"render " + kScene + " -o " + p + " --display " + p,
       "-o " + p + " and --display " + p + " name one file"},
      {"compare " + kScene + " " + kScene + " --json " + p + " --diff " + p,
       "--diff " + p + " and --json " + p + " name one file"},
      {"converge " + kScene + " --csv " + j + " --json " + j + " --plot " + j,
       "--csv " + j + " and --plot " + j + " name one file"}};
  for (const Case& c : cases) {
    const auto r = runGlint(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, c.says)) << c.args << "\n" << r.output;
    EXPECT_FALSE(contains(r.output, "rendering")) << c.args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(x));
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(j));
}

TEST(CommandPromises, ConvergeNamesAnUnreadableNumberInARecord) {
  // 1e999 overflows a double: nlohmann's out_of_range came out raw.
  const std::string frame = tmp("overflow.exr");
  {
    auto out = OIIO::ImageOutput::create(frame);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(1, 1, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("glint:passes", R"([{"spp": 1e999, "seconds": 1}])");
    ASSERT_TRUE(out->open(frame, spec));
    const float pixel[4] = {0, 0, 0, 1};
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixel));
    out->close();
  }
  const auto r = runGlint("converge --from-render " + frame);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(contains(r.output, frame + ": its glint:passes holds a value Glint cannot read"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "1e999")) << r.output;
  const std::string stats = test::writeTemp("overflow.json", R"({"passes": [{"spp": 1e999}]})");
  const auto s = runGlint("converge --from-render " + stats);
  EXPECT_EQ(s.exitCode, 2) << s.output;
  EXPECT_TRUE(contains(s.output, stats + ": its JSON holds a value Glint cannot read")) << s.output;
}

// As the unprivileged user nobody when the tests run as root (root passes every permission
// check, so a 000 scene or a 0555 directory would be read and written); skipped where setpriv
// is missing.
std::string asNobody() {
  if (::getuid() != 0) return "";
  if (!fs::exists("/usr/bin/setpriv")) return "(none)";
  return "/usr/bin/setpriv --reuid=65534 --regid=65534 --clear-groups";
}

TEST(CommandPromises, UnreadableScenesAndUnwritableDirectoriesAreFoundFirstWithExitTwo) {
  const std::string who = asNobody();
  if (who == "(none)") GTEST_SKIP() << "setpriv is needed to drop root's privileges";
  const fs::path dir = test::tempDir() / "permissions";
  fs::remove_all(dir);
  fs::create_directories(dir / "read-only");
  fs::permissions(dir, fs::perms::all);
  fs::permissions(dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec |
                                         fs::perms::group_read | fs::perms::group_exec |
                                         fs::perms::others_read | fs::perms::others_exec);
  const std::string scene = (dir / "scene.json").string();
  fs::copy_file(kScene, scene);
  fs::permissions(scene, fs::perms::none);
  // An input the user may not read is a bad argument, as a missing one is (exit 2).
  const auto r = runGlint("render " + scene + " -o " + (dir / "out.exr").string(), who);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot read JSON scene " + scene + ": Permission denied"))
      << r.output;
  // An output directory no file can be made in is found before the scene is loaded.
  fs::permissions(scene, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::string out = (dir / "read-only" / "out.exr").string();
  const auto w = runGlint("render " + scene + " -o " + out, who);
  EXPECT_EQ(w.exitCode, 2) << w.output;
  EXPECT_TRUE(contains(w.output, "cannot write " + out + ": no file can be made in " +
                                     (dir / "read-only").string() + " (Permission denied)"))
      << w.output;
  EXPECT_FALSE(contains(w.output, "rendering")) << w.output;
}

TEST(CommandPromises, AnOutputToStandardOutputIsAllThatStandardOutputCarries) {
  // compare, converge and validate printed their report on standard output before the JSON
  // asked for with `--json -`: a pipe into a JSON reader failed on the first line.
  const std::string frame = tmp("stdout-frame.exr");
  ASSERT_EQ(
      runGlint("render " + kScene + " --quiet --width 16 --height 12 --spp 4 -o " + frame).exitCode,
      0);
  const std::string errorsTo = "2>" + tmp("stdout-report.txt");
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"compare " + frame + " " + frame + " --json -", "rmse"},
      {"converge --from-render " + frame + " --json -", "from_render"},
      {"validate " + kScene + " --rays 64 --spp 0 --no-brute --json -", "disagreements"},
      {"render " + kScene + " --width 16 --height 12 --spp 4 -o " + tmp("stdout-render.exr") +
           " --stats-json -",
       "rays"}};
  for (const auto& [command, key] : commands) {
    const auto r = runGlint(command, "", errorsTo);
    ASSERT_EQ(r.exitCode, 0) << command << "\n" << r.output;
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.output)) << command << "\n" << r.output;
    EXPECT_TRUE(j.contains(key)) << command << "\n" << r.output;
  }
  // The report is still given, on standard error.
  const auto report = runGlint("compare " + frame + " " + frame + " --json -", "", errorsTo);
  EXPECT_EQ(report.output.find("rmse      0"), std::string::npos) << report.output;
  std::ifstream stderrText(tmp("stdout-report.txt"));
  const std::string said((std::istreambuf_iterator<char>(stderrText)), {});
  EXPECT_TRUE(contains(said, "rmse      0")) << said;
  // Two outputs cannot share it.
  const auto both = runGlint("converge --from-render " + frame + " --json - --csv -");
  EXPECT_EQ(both.exitCode, 2) << both.output;
  EXPECT_TRUE(contains(both.output, "--csv - and --json - both name standard output"))
      << both.output;
}

}  // namespace
}  // namespace glint
