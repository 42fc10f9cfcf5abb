// The command line contract of CLI.md: exit codes, messages, atomic output, determinism.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <OpenImageIO/imageio.h>
#include <glint_version.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "core/cpu_features.h"
#include "film/exr_output.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

// Every effect Glint has, so that determinism covers every sample dimension.
const char* kSmallScene = R"({
  "render": {"width": 40, "height": 30, "spp": 4, "seed": 3, "transparent_shadows": true},
  "camera": {"eye": [0,1,4], "look_at": [0,0.5,0], "aperture_radius": 0.05},
  "materials": {"m": {"type": "phong", "kd": [0.7,0.3,0.2], "ks": [0.3,0.3,0.3],
                      "km": [0.2,0.2,0.2], "gloss": 0.2},
                "g": {"type": "dielectric", "blur": 0.1}, "c": {"type": "mirror", "gloss": 0.05}},
  "lights": [{"type": "point", "position": [2,4,3]},
             {"type": "quad", "corner": [-1,3,0], "edge1": [0.5,0,0], "edge2": [0,0,0.5], "samples": 3},
             {"type": "disk", "center": [0,3,2], "normal": [0,-1,0], "radius": 0.3,
              "emission": "radiance", "samples": 2}],
  "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"},
              {"type": "sphere", "center": [-0.6,0.5,0], "radius": 0.5, "material": "g"},
              {"type": "sphere", "center": [0.6,0.5,0], "radius": 0.5, "material": "c"}]})";

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

TEST(Cli, VersionAndHelp) {
  const auto v = runGlint("--version");
  EXPECT_EQ(v.exitCode, 0);
  EXPECT_NE(v.output.find(std::string("glint ") + GLINT_VERSION), std::string::npos);
  EXPECT_EQ(runGlint("--help").exitCode, 0);
  const auto h = runGlint("render --help");
  EXPECT_EQ(h.exitCode, 0);
  EXPECT_NE(h.output.find("--spp"), std::string::npos);
  EXPECT_EQ(runGlint("render --no-such-flag").exitCode, 2);
}

TEST(Cli, InfoNamesTheCpuFeaturesGlintChoosesCodeBy) {
  // Read where every choice of code reads them (core/cpu_features.h), so that the line says
  // which copies a render runs.
  const auto r = runGlint("info");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("CPU ISA      " + cpuFeatureNames(cpuFeatures()) + "\n"),
            std::string::npos)
      << r.output;
}

TEST(Cli, InfoRefusesAnOcioConfigItWouldNotList) {
  // --ocio-config without --ocio was read by nothing and the info printed without a word.
  const auto r = runGlint("info --ocio-config /nonexistent.ocio");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--ocio-config requires --ocio"), std::string::npos) << r.output;
}

TEST(Cli, OutputNamesAreRefusedBeforeTheWork) {
  // A name past the file system's 255 bytes failed at the rename after the render (exit 1, the
  // frame lost); an empty output name was read as no output (exit 0, nothing written); a newline
  // in an output name reached the log as it is.
  const std::string scene = test::writeTemp("outputs.json", kSmallScene);
  const std::string dir = test::tempDir().string() + "/";
  const auto refused = [](const std::string& args, const std::string& why) {
    const auto r = runGlint(args);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(why), std::string::npos) << args << ": " << r.output;
  };
  refused("render " + scene + " --quiet -o " + dir + std::string(300, 'y') + ".exr",
          ": its name is 304 bytes; file names here have at most 255");
  refused("render " + scene + " --quiet -o '" + dir + "m\nglint: error: x.exr'",
          "a file name may not hold control characters");
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + dir + "outputs.exr").exitCode, 0);
  const std::string frame = dir + "outputs.exr";
  for (const std::string& args :
       {"render " + scene + " --quiet -o " + dir + "o2.exr --stats-json ''",
        "render " + scene + " --quiet -o " + dir + "o3.exr --display ''",
        "compare " + frame + " " + frame + " --json ''",
        "compare " + frame + " " + frame + " --diff ''",
        "validate " + scene + " --rays 10 --json ''", "bench " + scene + " --json ''",
        "converge " + scene + " --spp 1,2 --csv ''"})
    refused(args, "must not be empty; leave the option out instead");
  // Nothing to check passed every threshold (an agreement of 1 over no query).
  refused("validate " + scene + " --rays 0 --spp 0 --min-agreement 0.999",
          "--rays 0 with --spp 0 casts no ray: there would be nothing to check");
}

TEST(Cli, ANulInAMessageIsWrittenNotEndingIt) {
  // A key holding a NUL ended the message there, read as a C string: "objects[0].bogus" and no
  // reason.
  const std::string scene = test::writeTemp(
      "nul-key.json", R"({"camera": {"eye": [0,0,4], "look_at": [0,0,0]}, "bogus\u0000key": 1})");
  const auto r = runGlint("render " + scene + " -o " + (test::tempDir() / "nul.exr").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("bogus\\x00key: unknown key"), std::string::npos) << r.output;
}

TEST(Cli, SceneErrorExitsTwoWithLocation) {
  const std::string scene = test::writeTemp("bad.json",
                                            "{\n\"camera\": {\"eye\": [0,0,1],\n"
                                            "\"look_at\": [0,0,0], \"vfvo\": 3}}");
  const auto r = runGlint("render " + scene + " -o " + (test::tempDir() / "bad.exr").string());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find(scene + ":3: camera.vfvo: unknown key (did you mean \"vfov\"?)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(test::tempDir() / "bad.exr"));
  EXPECT_EQ(runGlint("render /no/such/scene.json").exitCode, 2);
}

TEST(Cli, FailedWriteLeavesThePreviousFileAndNoTemporaries) {
  const fs::path dir = test::tempDir() / "atomic";
  fs::create_directories(dir);
  const std::string scene = test::writeTemp("small.json", kSmallScene);
  const std::string target = (dir / "frame.exr").string();
  std::ofstream(target) << "previous contents";
  // A 1-block file size limit makes the EXR write fail part-way (EFBIG): exit 1, old file kept.
  const std::string cmd = "bash -c 'ulimit -f 1; exec " + std::string(GLINT_BINARY) + " render " +
                          scene + " --quiet --width 400 --height 300 --spp 1 -o " + target +
                          "' > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(slurp(target), "previous contents");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += bool(e.is_regular_file());
  EXPECT_EQ(entries, 1u) << "a temporary file was left behind";
  // A missing directory is a usage error, found before rendering.
  const auto m = runGlint("render " + scene + " --quiet -o /no/such/dir/x.exr");
  EXPECT_EQ(m.exitCode, 2);
  EXPECT_NE(m.output.find("does not exist"), std::string::npos) << m.output;
}

TEST(Cli, AReaderThatGoesAwayCostsTheLinesNotTheFrame) {
  // `glint render ... 2>&1 | head -1`: the reader (here `true`, which reads nothing) is gone
  // before the render's lines are written. Each write then fails with EPIPE; the frame must
  // still be rendered and written, exit 0 (it died of SIGPIPE, 141, and wrote nothing).
  const std::string scene = test::writeTemp("piped.json", kSmallScene);
  const std::string target = (test::tempDir() / "piped.exr").string();
  fs::remove(target);
  const std::string cmd = "bash -c '" + std::string(GLINT_BINARY) + " render " + scene +
                          " --width 40 --height 30 --spp 4 --stats -o " + target +
                          " 2>&1 | true; exit ${PIPESTATUS[0]}'";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(fs::exists(target));
}

TEST(Cli, OutputsNeverReplaceTheSceneALinkOrADevice) {
  // Each is refused before rendering, with exit 2, and left as it was.
  const fs::path dir = test::tempDir() / "refused";
  fs::create_directories(dir);
  const std::string scene = test::writeTemp("refused.json", kSmallScene);
  // -o scene.json is refused for its extension before anything is read (docs/output.md); the
  // stats JSON reaches the check of the run's inputs.
  const auto asFrame = runGlint("render " + scene + " --quiet -o " + scene);
  EXPECT_EQ(asFrame.exitCode, 2);
  EXPECT_EQ(slurp(scene), kSmallScene);
  const auto asScene = runGlint("render " + scene + " --quiet -o " + (dir / "s.exr").string() +
                                " --stats-json " + scene);
  EXPECT_EQ(asScene.exitCode, 2);
  EXPECT_NE(asScene.output.find("one of this run's inputs"), std::string::npos) << asScene.output;
  EXPECT_EQ(slurp(scene), kSmallScene);
  const fs::path link = dir / "link.png";
  fs::remove(link);
  fs::create_symlink(scene, link);
  const auto viaLink = runGlint("render " + scene + " --quiet --display " + link.string());
  EXPECT_EQ(viaLink.exitCode, 2);
  EXPECT_NE(viaLink.output.find("symbolic link"), std::string::npos) << viaLink.output;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(slurp(scene), kSmallScene);
  // A character device (the stats JSON to /dev/null) is refused too; "-" is standard output.
  const auto device = runGlint("render " + scene + " --quiet -o " + (dir / "a.exr").string() +
                               " --stats-json /dev/null");
  EXPECT_EQ(device.exitCode, 2);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const auto dash =
      runGlint("render " + scene + " --quiet -o " + (dir / "a.exr").string() + " --stats-json -");
  EXPECT_EQ(dash.exitCode, 0);
  EXPECT_NE(dash.output.find("\"rays_total\""), std::string::npos) << dash.output;
  // compare and converge refuse an output naming an input before their work: they printed
  // their figures, or rendered their whole series, and only then refused to write.
  const std::string frame = (dir / "a.exr").string();
  const auto compared = runGlint("compare " + frame + " " + frame + " --json " + frame);
  EXPECT_EQ(compared.exitCode, 2);
  EXPECT_NE(compared.output.find("one of this run's inputs"), std::string::npos) << compared.output;
  EXPECT_EQ(compared.output.find("rmse"), std::string::npos) << compared.output;
  const auto converged =
      runGlint("converge " + scene + " --width 8 --height 8 --spp 1 --json " + scene);
  EXPECT_EQ(converged.exitCode, 2);
  EXPECT_NE(converged.output.find("one of this run's inputs"), std::string::npos)
      << converged.output;
  EXPECT_EQ(converged.output.find("rmse"), std::string::npos) << converged.output;
  EXPECT_EQ(slurp(scene), kSmallScene);
}

TEST(Cli, OutOfRangeNumbersAreRefusedNotWrapped) {
  // An unsigned option given -1 or more than 2^64 − 1 would otherwise read as 2^64 − 1.
  const std::string scene = test::writeTemp("numbers.json", kSmallScene);
  const std::string out = " --quiet -o " + (test::tempDir() / "n.exr").string();
  for (const std::string bad : {"--seed -1", "--seed 100000000000000000000", "--seed 1e20"}) {
    const auto r = runGlint("render " + scene + out + " " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
  }
  EXPECT_EQ(runGlint("render " + scene + out + " --seed 18446744073709551615").exitCode, 0);
  const auto bench = runGlint("bench --procedural -1");
  EXPECT_EQ(bench.exitCode, 2);
  EXPECT_NE(bench.output.find("whole number"), std::string::npos) << bench.output;
  // A backend named twice was timed twice, its figures reported under one name.
  const auto twice = runGlint("bench " + scene + " --accel embree,bvh,embree");
  EXPECT_EQ(twice.exitCode, 2) << twice.output;
  EXPECT_NE(twice.output.find("--accel: \"embree\" is named twice"), std::string::npos)
      << twice.output;
}

TEST(Cli, AnEndlessSceneFileIsRefusedAtItsSizeLimit) {
  // /dev/zero never ends: read whole, it took all memory. Only regular files and pipes are read
  // as JSON scenes, so it is refused before a byte is read; a regular file is measured before
  // it is read (a sparse 129 MiB file: no byte of it is read), a pipe as it is read.
  const auto r = runGlint("render /dev/zero -o " + (test::tempDir() / "zero.exr").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("JSON scene /dev/zero is a character device; it must be a regular "
                          "file or a pipe"),
            std::string::npos)
      << r.output;
  const fs::path big = test::tempDir() / "big.json";
  std::ofstream(big) << "{}";
  fs::resize_file(big, (uint64_t{129} << 20));
  const auto sparse =
      runGlint("render " + big.string() + " -o " + (test::tempDir() / "big.exr").string());
  EXPECT_EQ(sparse.exitCode, 2) << sparse.output;
  EXPECT_NE(sparse.output.find("JSON scene " + big.string() +
                               " is 135266304 bytes; the limit is 128 MiB"),
            std::string::npos)
      << sparse.output;
  fs::remove(big);
}

TEST(Cli, EverySceneArgumentPassesTheInputFileCheck) {
  // glTF scene arguments were read without the checks JSON scenes had: a FIFO named f.gltf
  // blocked for ever, a link to /dev/zero read 2 GB, a sparse 3 GB .gltf read to the memory
  // cap. Every command that takes a scene refuses each with exit 2, naming the file, before
  // opening it. `timeout` bounds each run: a check that opened the FIFO would wait for ever.
  const fs::path dir = test::tempDir() / "hostile-scenes";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "f.gltf").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "z.glb");
  std::ofstream(dir / "big.gltf") << "{}";
  fs::resize_file(dir / "big.gltf", uint64_t{3} << 30);
  ASSERT_EQ(::mkfifo((dir / "f.obj").c_str(), 0600), 0);
  const std::pair<const char*, const char*> cases[] = {
      {"f.gltf", "is a FIFO; it must be a regular file"},
      {"z.glb", "is a character device; it must be a regular file"},
      {"big.gltf", "is 3221225472 bytes; the limit is 1024 MiB"},
      {"f.obj", "is a FIFO; it must be a regular file"}};
  for (const auto& [name, why] : cases)
    for (const auto& [command, options] : std::vector<std::pair<std::string, std::string>>{
             {"render", "--width 4 --height 4 -o " + (dir / "o.exr").string()},
             {"validate", "--rays 10"},
             {"bench", "--json " + (dir / "b.json").string()},
             {"info", ""},
             {"converge", "--spp 1 --json " + (dir / "c.json").string()}}) {
      const auto r = runGlint(command + " " + (dir / name).string() + " " + options, "timeout 20");
      EXPECT_EQ(r.exitCode, 2) << command << " " << name << ": " << r.output;
      EXPECT_NE(r.output.find((dir / name).string() + " " + why), std::string::npos)
          << command << " " << name << ": " << r.output;
    }
  fs::remove_all(dir);
}

TEST(Cli, NoInputReachesAnEmbreeAssertion) {
  // Embree aborts (exit 134) on a ray with a negative tmin, a NaN, a time outside [0, 1], or an
  // origin or direction coordinate past 1.844e18: validate's --ray is checked first (a
  // direction of -1e19 once aborted).
  for (const std::string bad :
       {"0 1 5 0 0 -1 -1 100 0", "nan 1 5 0 0 -1 0 100 0", "0 1 5 0 0 0 0 100 0",
        "0 1 5 0 0 -1 0 100 2", "0 0 5 0 0 -1e19 0 inf 0"}) {
    const auto r = runGlint("validate --ray \"" + bad + "\"");
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
  }
  // Geometry past ±1e18 from the camera (rays leaving it would start past Embree's range) and
  // a camera window whose span is not a float (its rays were NaN: render, validate, bench and
  // converge aborted) are scene errors, exit 2, before any ray is traced.
  const std::string far =
      test::writeTemp("far.json", R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
      "materials": {"m": {"type": "phong"}},
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"},
                  {"type": "quad", "corner": [1e19,0,0], "edge1": [1,0,0], "edge2": [0,1,0],
                   "material": "m"}]})");
  const auto v = runGlint("validate " + far + " --rays 2000");
  EXPECT_EQ(v.exitCode, 2) << v.output;
  EXPECT_NE(v.output.find("far.json:4: objects[1]: reaches past ±1e18 from the camera"),
            std::string::npos)
      << v.output;
  const std::string window = test::writeTemp("window.json", R"({"camera": {"eye": [0,0,5],
      "look_at": [0,0,0], "window": [-2e38, 2e38, -1, 1]}, "materials": {"m": {"type": "phong"}},
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const std::string out = (test::tempDir() / "window.exr").string();
  for (const std::string& command : {"render " + window + " -o " + out, "validate " + window,
                                     "bench " + window, "converge " + window + " --spp 1,2"}) {
    const auto r = runGlint(command);
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.output;
    EXPECT_NE(r.output.find("window.json:2: camera.window[0]: window values must lie within ±1e18"),
              std::string::npos)
        << command << ": " << r.output;
  }
}

TEST(Cli, FramesRenderARangeInOneProcessNumberedEitherWay) {
  // --frames 2-3 writes frames 2 and 3 (%04d numbering, Nuke's and ffmpeg's), each the same
  // pixels as its own --frame run (#### numbering) and tagged with its frame.
  const std::string scene = std::string(GLINT_SCENES_DIR) + "/animation.json";
  const std::string dir = test::tempDir().string();
  const std::string small = " --quiet --width 24 --height 16 --spp 2";
  ASSERT_EQ(
      runGlint("render " + scene + small + " --frames 2-3 -o " + dir + "/seq.%04d.exr").exitCode,
      0);
  for (int frame : {2, 3}) {
    const std::string f = std::to_string(frame);
    ASSERT_EQ(runGlint("render " + scene + small + " --frame " + f + " -o " + dir + "/one.####.exr")
                  .exitCode,
              0);
    const Image together = readImage(dir + "/seq.000" + f + ".exr");
    EXPECT_EQ(together.pixels, readImage(dir + "/one.000" + f + ".exr").pixels) << frame;
    auto in = OIIO::ImageInput::open(dir + "/seq.000" + f + ".exr");
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_int_attribute("glint:frame", -1), frame);
  }
  EXPECT_NE(readImage(dir + "/seq.0002.exr").pixels, readImage(dir + "/seq.0003.exr").pixels);
  // An output every frame would overwrite is refused before anything is rendered.
  const auto clash = runGlint("render " + scene + small + " --frames 1-2 -o " + dir + "/flat.exr");
  EXPECT_EQ(clash.exitCode, 2);
  EXPECT_NE(clash.output.find("number it with #### or %04d"), std::string::npos) << clash.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/flat.exr"));
  EXPECT_EQ(runGlint("render " + scene + small + " --frames 1-2 --frame 1").exitCode, 2);
}

TEST(Cli, SameImageForAnyThreadCountTileSizeAndCrop) {
  const std::string scene = test::writeTemp("det.json", kSmallScene);
  const auto path = [](const char* n) { return (test::tempDir() / n).string(); };
  ASSERT_EQ(runGlint("render " + scene + " --quiet --threads 1 --tile-size 64 -o " + path("a.exr"))
                .exitCode,
            0);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --threads 2 --tile-size 8 --tile-order row -o " +
                     path("b.exr"))
                .exitCode,
            0);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 5 25 3 17 -o " + path("c.exr")).exitCode,
            0);
  const Image a = readImage(path("a.exr")), b = readImage(path("b.exr")),
              c = readImage(path("c.exr"));
  EXPECT_EQ(a.pixels, b.pixels);  // bit for bit
  ASSERT_EQ(c.width, 20);
  ASSERT_EQ(c.height, 14);
  EXPECT_EQ(c.x, 5);  // the data window sits inside the full display window
  EXPECT_EQ(c.y, 3);
  EXPECT_EQ(c.fullWidth, 40);
  for (int y = 0; y < 14; ++y)
    for (int x = 0; x < 20; ++x)
      for (int ch = 0; ch < 4; ++ch)
        ASSERT_EQ(c.pixels[(size_t(y) * 20 + size_t(x)) * 4 + size_t(ch)],
                  a.pixels[(size_t(y + 3) * 40 + size_t(x + 5)) * 4 + size_t(ch)]);
}

TEST(Cli, EveryBackendRendersTheSameImage) {
  // The backends share every intersection routine (the scene has spheres, a plane and, in the
  // area lights, no triangles) and differ only in traversal, so the images must agree exactly,
  // for every sampled effect too.
  const std::string scene = test::writeTemp("backends.json", kSmallScene);
  const auto path = [](const std::string& n) { return (test::tempDir() / (n + ".exr")).string(); };
  for (const char* accel : {"embree", "bvh", "brute", "grid", "octree", "kdtree",
                            "octree-generate-and-test", "rayclass", "coherence", "spheres"})
    ASSERT_EQ(
        runGlint("render " + scene + " --quiet --accel " + accel + " -o " + path(accel)).exitCode,
        0);
  const auto embree = readImage(path("embree")).pixels;
  EXPECT_EQ(readImage(path("bvh")).pixels, embree);
  EXPECT_EQ(readImage(path("brute")).pixels, embree);
  EXPECT_EQ(readImage(path("grid")).pixels, embree);
  EXPECT_EQ(readImage(path("octree")).pixels, embree);
  EXPECT_EQ(readImage(path("kdtree")).pixels, embree);
  EXPECT_EQ(readImage(path("rayclass")).pixels, embree);
  EXPECT_EQ(readImage(path("octree-generate-and-test")).pixels, embree);
  EXPECT_EQ(readImage(path("coherence")).pixels, embree);
  EXPECT_EQ(readImage(path("spheres")).pixels, embree);
}

TEST(Cli, DefaultSceneRendersWithStats) {
  const std::string out = (test::tempDir() / "default.exr").string();
  const std::string json = (test::tempDir() / "stats.json").string();
  const auto r =
      runGlint("render --quiet --width 64 --height 40 --spp 1 -o " + out + " --display " +
               (test::tempDir() / "default.png").string() + " --stats-json " + json);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Image img = readImage(out);
  EXPECT_EQ(img.width, 64);
  EXPECT_TRUE(fs::exists(test::tempDir() / "default.png"));
  const std::string stats = slurp(json);
  for (const char* key : {"\"seconds\"", "\"rays_total\"", "\"nonfinite_samples\": 0",
                          "\"features_used\"", "\"features_left_out\""})
    EXPECT_NE(stats.find(key), std::string::npos) << key;
  // The process's peak resident set: at least what its libraries take mapped (glint --version
  // alone peaks at 14.5 MB), and far below a gigabyte for a 64 x 40 frame.
  const double peak = nlohmann::json::parse(stats).at("peak_rss_bytes").get<double>();
  EXPECT_GT(peak, 8e6);
  EXPECT_LT(peak, 1e9);
}

TEST(Cli, ConvergeRefusesListsOfNothingAndAReferencePastTheSampler) {
  // `--spp ,` left no sample count and crashed (the largest of none); `--accel ,` and
  // `--sampler ,` silently fell back to a default or to no series. The default reference, 16 ×
  // the largest spp, overflowed int at 2^27 (a reference of -2^31, then 0, spp); every case is
  // refused before any ray is traced.
  const std::string scene = test::writeTemp("converge-lists.json", R"({
    "render": {"width": 4, "height": 4},
    "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  for (const auto& [args, error] : std::vector<std::pair<std::string, std::string>>{
           {"--spp ,", "--spp: name at least one sample count"},
           {"--spp 1 --accel ,", "--accel: name at least one backend"},
           {"--spp 1 --sampler ,,", "--sampler: name at least one sampler"},
           {"--spp 268435457", "--spp: 268435457 is more than the sampler's limit of 268435456"},
           {"--spp 1,134217728",
            "the reference would take 16 × the largest --spp = 2147483648 spp, more than the "
            "sampler's limit of 268435456: give --reference-spp or --reference"}}) {
    const auto r = runGlint("converge " + scene + " " + args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("glint: error: " + error), std::string::npos) << args << "\n"
                                                                          << r.output;
  }
}

TEST(Cli, ConvergeReportsErrorAgainstSppWithItsReference) {
  // Pixel jitter alone over a sphere, a plane and a soft shadow; `random` draws independent
  // samples, so RMSE ∝ spp^−½. Against a reference of 16 × 16 = 256 stratified spp whose own
  // error adds σ²/256 to each MSE, the slope from 1 to 16 spp is ½·log(1/16 + 1/256)/log 16
  // = −0.489. The image MSE is itself an estimate, carried by the pixels on an edge or in the
  // penumbra: weighting pixels by their variance v (the variance AOV at 16 spp), (Σv)²/Σv² =
  // 30 pixels effectively carry it. A mean of 30 squared errors, each χ² with one degree of
  // freedom, has a relative σ of √(2/30) = 0.26, so the slope over a factor 16 has
  // σ = √2·0.26/(2·ln 16) = 0.066; the tolerance is 3σ (measured: −0.515).
  const std::string scene = test::writeTemp("converge.json", R"({
    "render": {"width": 24, "height": 16, "seed": 9},
    "camera": {"eye": [0, 1.5, 4], "look_at": [0, 0.5, 0], "vfov": 40},
    "materials": {"m": {"type": "phong", "kd": [0.8, 0.8, 0.8]}},
    "lights": [{"type": "quad", "corner": [-0.5, 3, -0.5], "edge1": [1, 0, 0],
                "edge2": [0, 0, 1], "samples": 2}],
    "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "m"},
                {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.6, "material": "m"}]})");
  const std::string json = (test::tempDir() / "converge_out.json").string();
  const auto r = runGlint("converge " + scene + " --spp 1,4,16 --sampler random --json " + json);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(j["width"], 24);
  EXPECT_EQ(j["height"], 16);
  EXPECT_EQ(j["reference"]["spp"], 256);
  EXPECT_EQ(j["reference"]["sampler"], "stratified");
  ASSERT_EQ(j["series"].size(), 1u);
  const auto& points = j["series"][0]["points"];
  ASSERT_EQ(points.size(), 3u);
  EXPECT_GT(points[0]["rmse"].get<double>(), points[1]["rmse"].get<double>());
  EXPECT_GT(points[1]["rmse"].get<double>(), points[2]["rmse"].get<double>());
  EXPECT_NEAR(j["series"][0]["spp_slope"].get<double>(), -0.489, 3 * 0.066);
}

}  // namespace
}  // namespace glint
