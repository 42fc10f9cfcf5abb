// Animated scenes (io/animation.h, docs/scene-format.md#animation): keys spread over frames, a
// Scene per frame whose motion covers only that frame's shutter, and the frame on the command
// line (`--frame`, `####` names, the settings hash, `glint plan`).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "film/exr_output.h"
#include "io/animation.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

Scene load(const std::string& text, std::optional<int> frame = std::nullopt) {
  return loadSceneText(text, "anim.json", GLINT_SCENES_DIR, frame);
}

std::vector<float> render(const Scene& s) {
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  RenderOptions opt;
  opt.progress = false;
  return renderScene(s, *accel, opt).film.toFloatRgba();
}

const char* kCommon = R"(
  "render": {"width": 32, "height": 24, "spp": 4, "background": [0.1,0.2,0.3]},
  "materials": {"m": {"type": "phong", "kd": [0.8,0.5,0.3], "ks": [0.3,0.3,0.3]}},
  "lights": [{"type": "point", "position": [2,4,5]}],)";

std::string scene(const std::string& extra, const std::string& camera, const std::string& objects) {
  return std::string("{") + kCommon + extra + R"("camera": )" + camera + R"(, "objects": [)" +
         objects + "]}";
}

// Frames 1 … 3; a sphere with centre keys on frames 1, 2, 3 and a camera with keys there too.
const std::string kAnimated = scene(R"("animation": {"frames": [1, 3]},)",
                                    R"({"shutter": [0, 0], "keys": [
      {"eye": [-1,1,6], "look_at": [0,0.5,0]}, {"eye": [0,1,6], "look_at": [0,0.5,0]},
      {"eye": [1,1,6], "look_at": [0,0.5,0], "up": [0,1,0]}]})",
                                    R"({"type": "sphere", "center": [-1,0.5,0], "radius": 0.5,
      "material": "m", "motion": {"center": [[-1,0.5,0], [0,0.5,0], [1,1,0]]}})");

TEST(Animation, AFrameOnAKeyIsTheStillSceneThereBitForBit) {
  // Frame 2 sits on the middle keys of both the camera and the sphere: with the shutter closed
  // it is an ordinary still scene with the camera at (0,1,6) and the sphere at (0,0.5,0).
  const Scene frame2 = load(kAnimated, 2);
  EXPECT_FALSE(frame2.features.motion) << "a closed shutter leaves no motion in the frame";
  ASSERT_TRUE(frame2.animation.has_value());
  EXPECT_EQ(frame2.animation->frame, 2);
  const std::string still = scene("", R"({"eye": [0,1,6], "look_at": [0,0.5,0]})",
                                  R"({"type": "sphere", "center": [0,0.5,0], "radius": 0.5,
      "material": "m"})");
  EXPECT_EQ(render(frame2), render(load(still)));
  // The last frame is on the last keys.
  const std::string last = scene("", R"({"eye": [1,1,6], "look_at": [0,0.5,0]})",
                                 R"({"type": "sphere", "center": [1,1,0], "radius": 0.5,
      "material": "m"})");
  EXPECT_EQ(render(load(kAnimated, 3)), render(load(last)));
  // Without --frame a scene is its first frame.
  EXPECT_EQ(load(kAnimated).animation->frame, 1);
  EXPECT_NE(render(load(kAnimated)), render(load(kAnimated, 2))) << "the frames must differ";
}

TEST(Animation, MeshAndTransformKeysOnAFrameAreThoseKeysBitForBit) {
  // Frames 0 … 4 with three keys at 0, 2, 4; frame 4 is the last keys. A deforming mesh there is
  // the still mesh with the last key's vertices; an instance moved by transform keys is the
  // instance placed by the last key — written as two equal keys, which load as that one placed
  // instance (equal keys are a static object).
  const std::string group = R"("groups": {"g": [{"type": "box", "min": [-0.3,-0.3,-0.3],
      "max": [0.3,0.3,0.3], "material": "m"}]},)";
  const std::string camera = R"({"eye": [0,1,6], "look_at": [0,0.5,0]})";
  const std::string animated = scene(R"("animation": {"frames": [0, 4]},)" + group, camera, R"(
    {"type": "mesh", "positions": [[-2,0,0],[-1,0,0],[-2,1,0]], "indices": [[0,1,2]],
     "material": "m", "motion": {"positions": [[[-2,0,0],[-1,0,0],[-2,1,0]],
        [[-2,0,-1],[-1,0,-1],[-2,2,-1]], [[-2,0.5,0],[-1,0.5,0],[-2,1.5,0.5]]]}},
    {"type": "instance", "group": "g", "motion": {"transform": [
      {"translate": [1,0.5,0]}, {"translate": [1,1,0], "rotate": [0,1,0,40]},
      {"translate": [1.5,1,0], "rotate": [0,1,0,80], "scale": [1,2,1]}]}})");
  const std::string still = scene(group, camera, R"(
    {"type": "mesh", "positions": [[-2,0.5,0],[-1,0.5,0],[-2,1.5,0.5]], "indices": [[0,1,2]],
     "material": "m"},
    {"type": "instance", "group": "g", "motion": {"transform": [
      {"translate": [1.5,1,0], "rotate": [0,1,0,80], "scale": [1,2,1]},
      {"translate": [1.5,1,0], "rotate": [0,1,0,80], "scale": [1,2,1]}]}})");
  const Scene frame4 = load(animated, 4);
  EXPECT_FALSE(frame4.features.motion);
  EXPECT_EQ(render(frame4), render(load(still)));
  EXPECT_NE(render(load(animated, 2)), render(frame4)) << "the frames must differ";
}

TEST(Animation, AnOpenShutterBlursOverJustThatFrame) {
  // Shutter [0, 0.5] at frame 2: the sphere sweeps frames 2 … 2.5, from key (0,0.5,0) half-way
  // to (1,1,0), i.e. to (0.5,0.75,0) (exact in float). That is a still-camera scene whose keys
  // span a full shutter [0, 1].
  const std::string animated =
      scene(R"("animation": {"frames": [1, 3]},)",
            R"({"eye": [0,1,6], "look_at": [0,0.5,0], "shutter": [0, 0.5]})",
            R"({"type": "sphere", "center": [-1,0.5,0], "radius": 0.5,
      "material": "m", "motion": {"center": [[-1,0.5,0], [0,0.5,0], [1,1,0]]}})");
  const std::string blurred =
      scene("", R"({"eye": [0,1,6], "look_at": [0,0.5,0], "shutter": [0, 1]})",
            R"({"type": "sphere", "center": [0,0.5,0], "radius": 0.5,
      "material": "m", "motion": {"center": [[0,0.5,0], [0.5,0.75,0]]}})");
  const Scene frame2 = load(animated, 2);
  EXPECT_TRUE(frame2.features.motion);
  ASSERT_EQ(frame2.sphereCenterKeys[0].size(), 2u) << "no key inside (2, 2.5): two keys suffice";
  EXPECT_EQ(render(frame2), render(load(blurred)));
}

TEST(Animation, KeysInsideTheShutterAreKept) {
  // Frames 0 … 2 with five keys: keys sit every half frame. Frame 1's shutter [0, 1] spans
  // frames 1 … 2 with a key (a bend in the path) at 1.5, so three evenly spaced keys at 1, 1.5
  // and 2 reproduce the path exactly — the scene with those keys over [0, 1].
  const std::string animated = scene(R"("animation": {"frames": [0, 2]},)",
                                     R"({"eye": [0,1,6], "look_at": [0,0.5,0], "shutter": [0, 1]})",
                                     R"({"type": "sphere", "center": [-1,0.5,0], "radius": 0.5,
      "material": "m", "motion": {"center": [[-2,0.5,0], [-1,0.5,0], [0,0.5,0], [0,1.5,0],
                                             [1,1.5,0]]}})");
  const std::string same = scene("", R"({"eye": [0,1,6], "look_at": [0,0.5,0], "shutter": [0, 1]})",
                                 R"({"type": "sphere", "center": [0,0.5,0], "radius": 0.5,
      "material": "m", "motion": {"center": [[0,0.5,0], [0,1.5,0], [1,1.5,0]]}})");
  const Scene frame1 = load(animated, 1);
  ASSERT_EQ(frame1.sphereCenterKeys[0].size(), 3u);
  EXPECT_EQ(render(frame1), render(load(same)));
}

TEST(Animation, KeyPositionsAreExactOnKeysAndClampedPastTheEnds) {
  const Animation a{1, 3, 1};
  // Three keys over frames 1 … 3: frame 2 is key 1 exactly, 2.5 half-way to key 2.
  EXPECT_EQ(keyPosition(a, 3, 2).segment, 1u);
  EXPECT_EQ(keyPosition(a, 3, 2).fraction, 0.0);
  EXPECT_EQ(keyPosition(a, 3, 2.5).fraction, 0.5);
  // Past the last frame (a shutter open beyond it) the last key holds: segment 1, fraction 1.
  EXPECT_EQ(keyPosition(a, 3, 3.5).segment, 1u);
  EXPECT_EQ(keyPosition(a, 3, 3.5).fraction, 1.0);
  // Frames 0 … 24 with 4 keys (every 8 frames): frame 16 is key 2 exactly.
  const KeyPosition p = keyPosition({0, 24, 0}, 4, 16);
  EXPECT_EQ(p.segment, 2u);
  EXPECT_EQ(p.fraction, 0.0);
}

std::string errorOf(const std::string& text, std::optional<int> frame = std::nullopt) {
  try {
    load(text, frame);
  } catch (const GlintError& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(Animation, MistakesNameTheKeyOrTheRange) {
  EXPECT_EQ(errorOf(kAnimated, 4),
            "--frame 4 is outside the scene's frames 1-3 (animation.frames)");
  EXPECT_THROW(load(kAnimated, 4), UsageError);
  EXPECT_EQ(errorOf(kAnimated, 0),
            "--frame 0 is outside the scene's frames 1-3 (animation.frames)");
  const std::string still = scene("", R"({"eye": [0,1,6], "look_at": [0,0.5,0]})", "");
  EXPECT_EQ(errorOf(still, 1),
            "--frame 1: the scene is not animated (it declares no \"animation\")");
  EXPECT_EQ(errorOf(scene(R"("animation": {"frames": [3, 1]},)",
                          R"({"eye": [0,1,6], "look_at": [0,0.5,0]})", "")),
            "anim.json:4: animation.frames: the last frame must come after the first");
  EXPECT_EQ(errorOf(scene(R"("animation": {"frame": [1, 3]},)",
                          R"({"eye": [0,1,6], "look_at": [0,0.5,0]})", "")),
            "anim.json:4: animation.frame: unknown key (did you mean \"frames\"?)");
  // Camera keys need an animation, at least two keys, and replace eye/look_at/up.
  const std::string keys = R"("keys": [{"eye": [0,1,6], "look_at": [0,0,0]},
                                       {"eye": [1,1,6], "look_at": [0,0,0]}])";
  EXPECT_NE(errorOf(scene("", "{" + keys + "}", ""))
                .find("camera.keys: camera keys are spread over the frames of an animation"),
            std::string::npos);
  EXPECT_NE(
      errorOf(scene(R"("animation": {"frames": [1, 3]},)", R"({"eye": [0,1,6], )" + keys + "}", ""))
          .find("camera.eye: the camera's \"keys\" replace eye, look_at and up"),
      std::string::npos);
  EXPECT_NE(errorOf(scene(R"("animation": {"frames": [1, 3]},)",
                          R"({"keys": [{"eye": [0,1,6], "look_at": [0,0,0]}]})", ""))
                .find("camera.keys: must list at least 2 keys"),
            std::string::npos);
  EXPECT_NE(errorOf(scene(R"("animation": {"frames": [1, 3]},)",
                          R"({"keys": [{"eye": [0,1,6], "look_at": [0,1,6]},
                                       {"eye": [1,1,6], "look_at": [0,0,0]}]})",
                          ""))
                .find("camera.keys[0]: eye and look_at are the same point"),
            std::string::npos);
  // Keys that are each sound can blend into a pose that is not: the eye passes through the
  // point it looks at halfway, at frame 1. The error names that frame and the keys around it.
  const std::string passing = scene(R"("animation": {"frames": [0, 2]},)",
                                    R"({"keys": [{"eye": [0,1,6], "look_at": [0,1,0]},
                                                 {"eye": [0,1,-6], "look_at": [0,1,0]}]})",
                                    "");
  EXPECT_NO_THROW(load(passing, 0));
  EXPECT_NE(errorOf(passing, 1)
                .find("camera.keys: at frame 1, between keys[0] and keys[1]: eye and look_at are "
                      "the same point"),
            std::string::npos)
      << errorOf(passing, 1);
}

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

std::string attribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  return in ? std::string(in->spec().get_string_attribute(name)) : "(unreadable)";
}

TEST(Animation, TheCommandLineNamesFramesAndKeepsThemApart) {
  const std::string file = test::writeTemp("anim.json", kAnimated);
  // `####` becomes the zero-padded frame number.
  ASSERT_EQ(runGlint("render " + file + " --quiet --frame 2 -o " + tmp("a.####.exr")).exitCode, 0);
  EXPECT_TRUE(fs::exists(tmp("a.0002.exr")));
  {
    auto in = OIIO::ImageInput::open(tmp("a.0002.exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_int_attribute("glint:frame", -1), 2);
  }
  // A frame outside the range is a usage error naming it.
  const auto outside = runGlint("render " + file + " --quiet --frame 9 -o " + tmp("b.exr"));
  EXPECT_EQ(outside.exitCode, 2);
  EXPECT_NE(outside.output.find("--frame 9 is outside the scene's frames 1-3"), std::string::npos)
      << outside.output;
  // --frames is named as given, not as its first frame ("--frame 0"), also on a still scene.
  const auto before = runGlint("render " + file + " --quiet --frames 0-2 -o " + tmp("c.####.exr"));
  EXPECT_EQ(before.exitCode, 2);
  EXPECT_NE(before.output.find("--frames 0-2 is outside the scene's frames 1-3"), std::string::npos)
      << before.output;
  const std::string still = test::writeTemp(
      "still.json", R"({"camera": {"eye": [0,0,4], "look_at": [0,0,0]}, "objects": []})");
  const auto stillFrames =
      runGlint("render " + still + " --quiet --frames 0-1 -o " + tmp("s.####.exr"));
  EXPECT_EQ(stillFrames.exitCode, 2);
  EXPECT_NE(stillFrames.output.find(
                "--frames 0-1: the scene is not animated (it declares no \"animation\")"),
            std::string::npos)
      << stillFrames.output;
  EXPECT_FALSE(fs::exists(tmp("c.0000.exr")) || fs::exists(tmp("c.0001.exr")) ||
               fs::exists(tmp("s.0000.exr")));
  // An empty --frames read as none given: the first frame rendered, to an unnumbered file.
  for (const char* command : {"render", "plan"}) {
    const auto empty =
        runGlint(std::string(command) + " " + file + " --frames '' -o " + tmp("e.exr"));
    EXPECT_EQ(empty.exitCode, 2) << command;
    EXPECT_NE(empty.output.find("--frames: must not be empty"), std::string::npos) << empty.output;
  }
  EXPECT_FALSE(fs::exists(tmp("e.exr")));
  // Crops of two frames carry different settings hashes, so merge refuses to mix them.
  ASSERT_EQ(runGlint("render " + file + " --quiet --frame 1 --crop 0 16 0 24 -o " + tmp("l1.exr"))
                .exitCode,
            0);
  ASSERT_EQ(runGlint("render " + file + " --quiet --frame 2 --crop 16 32 0 24 -o " + tmp("r2.exr"))
                .exitCode,
            0);
  EXPECT_NE(attribute(tmp("l1.exr"), "glint:settings_hash"),
            attribute(tmp("r2.exr"), "glint:settings_hash"));
  const auto mixed = runGlint("merge " + tmp("m.exr") + " " + tmp("l1.exr") + " " + tmp("r2.exr"));
  EXPECT_EQ(mixed.exitCode, 2);
  EXPECT_NE(mixed.output.find("different scene or settings"), std::string::npos) << mixed.output;
}

TEST(Animation, PlanListsFramesOutputsAndTiles) {
  const std::string file = test::writeTemp("plan.json", kAnimated);
  const auto plan = runGlint("plan " + file + " --tiles 4 --frames 2-3 -o out/a.####.exr");
  ASSERT_EQ(plan.exitCode, 0) << plan.output;
  // 32 × 24 in 4 tiles: 2 × 2 of 16 × 12.
  for (const char* line :
       {"size 32 24\n", "frames 2 3\n", "grid 2 2\n", "output 2 out/a.0002.exr\n",
        "output 3 out/a.0003.exr\n", "tile 0 0 16 0 12\n", "tile 3 16 32 12 24\n"})
    EXPECT_NE(plan.output.find(line), std::string::npos) << line << plan.output;
  EXPECT_EQ(plan.output.find("output 1 "), std::string::npos) << "frame 1 was not asked for";
  const auto outside = runGlint("plan " + file + " --frames 2-5");
  EXPECT_EQ(outside.exitCode, 2);
  EXPECT_NE(outside.output.find("--frames 2-5 lies outside the scene's frames 1-3"),
            std::string::npos)
      << outside.output;
  const auto unnamed = runGlint("plan " + file + " -o a.exr");
  EXPECT_EQ(unnamed.exitCode, 2);
  EXPECT_NE(unnamed.output.find("3 frames need a run of # in the file name"), std::string::npos)
      << unnamed.output;
}

TEST(Animation, MergeRefusesTilesOfAnotherSceneFile) {
  // A farm passes the scene hash it planned with: tiles rendered after the scene file changed
  // are refused, even when they agree with each other.
  const std::string file = test::writeTemp("hash.json", kAnimated);
  ASSERT_EQ(runGlint("render " + file + " --quiet -o " + tmp("h.exr")).exitCode, 0);
  const std::string hash = attribute(tmp("h.exr"), "glint:scene_hash");
  EXPECT_EQ(
      runGlint("merge " + tmp("h2.exr") + " " + tmp("h.exr") + " --scene-hash " + hash).exitCode,
      0);
  const auto other =
      runGlint("merge " + tmp("h3.exr") + " " + tmp("h.exr") + " --scene-hash 0123456789abcdef");
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_NE(other.output.find("was rendered from another scene file (glint:scene_hash " + hash +
                              ", expected 0123456789abcdef)"),
            std::string::npos)
      << other.output;
  // An empty hash checked nothing: every crop merged.
  const auto empty = runGlint("merge " + tmp("h4.exr") + " " + tmp("h.exr") + " --scene-hash ''");
  EXPECT_EQ(empty.exitCode, 2);
  EXPECT_NE(empty.output.find("--scene-hash: must not be empty"), std::string::npos)
      << empty.output;
  EXPECT_FALSE(std::filesystem::exists(tmp("h4.exr")));
}

}  // namespace
}  // namespace glint
