// Frame output: EXR options and metadata, interrupted renders, crops merged into the frame.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "camera/camera.h"
#include "film/exr_output.h"
#include "film/merge.h"
#include "test_util.h"

namespace glint {
namespace {

using test::runGlint;
namespace fs = std::filesystem;

const char* kScene = R"({
  "render": {"width": 48, "height": 32, "spp": 4, "seed": 5},
  "camera": {"eye": [0,0,5], "look_at": [0,0,0], "vfov": 40},
  "materials": {"m": {"type": "phong", "kd": [0.6,0.4,0.3], "ks": [0.3,0.3,0.3]},
                "g": {"type": "dielectric"}},
  "lights": [{"type": "quad", "corner": [-1,3,1], "edge1": [1,0,0], "edge2": [0,0,1], "samples": 2}],
  "objects": [{"type": "plane", "point": [0,-1,0], "normal": [0,1,0], "material": "m"},
              {"type": "sphere", "center": [-0.6,0,0], "radius": 0.7, "material": "g"},
              {"type": "sphere", "center": [0.8,-0.3,0.5], "radius": 0.5, "material": "m"}]})";

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

OIIO::ImageSpec specOf(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  return in ? in->spec() : OIIO::ImageSpec{};
}

TEST(Output, MetadataHalfAndCompression) {
  const std::string scene = test::writeTemp("out_scene.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + tmp("meta.exr")).exitCode, 0);
  const OIIO::ImageSpec s = specOf(tmp("meta.exr"));
  EXPECT_EQ(s.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(s.get_string_attribute("compression"), "zip");
  EXPECT_EQ(s.get_int_attribute("glint:spp"), 4);
  EXPECT_EQ(s.get_string_attribute("glint:seed"), "5");
  EXPECT_EQ(s.get_string_attribute("glint:sampler"), "stratified");
  EXPECT_EQ(s.get_string_attribute("glint:crop"), "0 48 0 32");
  EXPECT_EQ(s.get_int_attribute("glint:partial", -1), 0);
  EXPECT_EQ(s.get_string_attribute("glint:colorspace"), "lin_rec709");
  EXPECT_EQ(s.get_string_attribute("glint:settings_hash").size(), 16u);
  EXPECT_NE(s.get_string_attribute("glint:commandline").find("--quiet"), std::string::npos);
  EXPECT_NE(s.find_attribute("worldToCamera", OIIO::TypeMatrix44), nullptr);
  EXPECT_NE(s.find_attribute("worldToNDC", OIIO::TypeMatrix44), nullptr);

  ASSERT_EQ(runGlint("render " + scene + " --quiet --half --compression piz -o " + tmp("half.exr"))
                .exitCode,
            0);
  const OIIO::ImageSpec h = specOf(tmp("half.exr"));
  EXPECT_EQ(h.format, OIIO::TypeDesc::HALF);
  EXPECT_EQ(h.get_string_attribute("compression"), "piz");
  EXPECT_EQ(runGlint("render " + scene + " --quiet --compression lzma -o " + tmp("x.exr")).exitCode,
            2);
}

TEST(Output, NonSquarePixelsAreStatedInTheFrameAndItsMerge) {
  // A window of aspect 2 on a square image: each pixel is twice as wide as it is tall. The EXR
  // said 1 (OpenEXR's default), so Nuke and oiiotool showed the frame squeezed to half its
  // width. Its crops, merged, keep what they say.
  std::string text = kScene;
  const std::string vfov = R"("vfov": 40)";
  text.replace(text.find(vfov), vfov.size(), R"("window": [-0.8, 0.8, -0.2, 0.2])");
  const std::string wide = test::writeTemp("wide-pixels.json", text);
  // 48 × 32 pixels over 1.6 × 0.4: (1.6 / 48) / (0.4 / 32) = 8 / 3.
  const std::string left = tmp("wide-left.exr"), right = tmp("wide-right.exr");
  ASSERT_EQ(runGlint("render " + wide + " --quiet --crop 0 20 0 32 -o " + left).exitCode, 0);
  ASSERT_EQ(runGlint("render " + wide + " --quiet --crop 20 48 0 32 -o " + right).exitCode, 0);
  const float ratio = specOf(left).get_float_attribute("PixelAspectRatio");
  EXPECT_FLOAT_EQ(ratio, 8.0f / 3);
  EXPECT_EQ(specOf(right).get_float_attribute("PixelAspectRatio"), ratio);
  const std::string merged = tmp("wide-merged.exr");
  ASSERT_EQ(runGlint("merge " + merged + " " + left + " " + right).exitCode, 0);
  EXPECT_EQ(specOf(merged).get_float_attribute("PixelAspectRatio"), ratio);
  // Square pixels (the vfov's window follows the image's aspect) say 1.
  const std::string square = test::writeTemp("square-pixels.json", kScene);
  ASSERT_EQ(runGlint("render " + square + " --quiet -o " + tmp("square.exr")).exitCode, 0);
  EXPECT_EQ(specOf(tmp("square.exr")).get_float_attribute("PixelAspectRatio", -1), 1.0f);
}

// A point through an EXR's standard matrix as OpenEXR's tools apply it: Imath's row vector
// p' = p·M, then the divide by w (Imath's multVecMatrix).
Vec3d throughExrMatrix(const OIIO::ImageSpec& spec, const char* name, Vec3d p) {
  const OIIO::ParamValue* a = spec.find_attribute(name, OIIO::TypeMatrix44);
  if (!a) {
    ADD_FAILURE() << "no " << name;
    return {};
  }
  const float* m = static_cast<const float*>(a->data());
  double out[4];
  for (int c = 0; c < 4; ++c) out[c] = p.x * m[c] + p.y * m[4 + c] + p.z * m[8 + c] + m[12 + c];
  return {out[0] / out[3], out[1] / out[3], out[2] / out[3]};
}

TEST(Output, CameraMatricesFollowTheOpenExrStandard) {
  // ImfStandardAttributes.h: worldToCamera maps into a left-handed space, the camera at the
  // origin looking down +z, x right, y up; worldToNDC maps to (0, 0) at the top-left and
  // (1, 1) at the bottom-right of the display window. Camera at (0,0,5) looking at the origin,
  // vfov 40°, 48×32: half extents at distance 1 are hh = tan 20° = 0.363970, hw = 1.5·hh.
  const std::string scene = test::writeTemp("matrices.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + tmp("matrices.exr")).exitCode, 0);
  const OIIO::ImageSpec s = specOf(tmp("matrices.exr"));
  const double hh = std::tan(20.0 * M_PI / 180), hw = 1.5 * hh;
  struct Case {
    Vec3d world, camera, ndc;
  };
  const Case cases[] = {
      {{0, 0, 0}, {0, 0, 5}, {0.5, 0.5, 0}},             // the look-at point, centred
      {{1, 0, 0}, {1, 0, 5}, {0.5 + 0.1 / hw, 0.5, 0}},  // right of it: x grows
      {{0, 1, 0}, {0, 1, 5}, {0.5, 0.5 - 0.1 / hh, 0}},  // above it: NDC y shrinks
      {{-2, -1, -5}, {-2, -1, 10}, {0.5 - 0.1 / hw, 0.5 + 0.05 / hh, 0}},  // farther: ÷ depth
  };
  for (const Case& c : cases) {
    const Vec3d cam = throughExrMatrix(s, "worldToCamera", c.world);
    const Vec3d ndc = throughExrMatrix(s, "worldToNDC", c.world);
    // float matrices: a few ulps of 5.
    EXPECT_NEAR(cam.x, c.camera.x, 1e-5);
    EXPECT_NEAR(cam.y, c.camera.y, 1e-5);
    EXPECT_NEAR(cam.z, c.camera.z, 1e-5);
    EXPECT_NEAR(ndc.x, c.ndc.x, 1e-6);
    EXPECT_NEAR(ndc.y, c.ndc.y, 1e-6);
  }
  // The corners of the frame: a point on the ray through pixel corner (x, y) lands on
  // (x/48, y/32); an off-axis orthographic camera as well.
  for (const char* camera : {R"("eye": [1,2,5], "look_at": [0,0.5,0], "vfov": 30)",
                             R"("type": "orthographic", "eye": [1,2,5], "look_at": [0,0.5,0],
                                "height": 3)"}) {
    const std::string original = R"("eye": [0,0,5], "look_at": [0,0,0], "vfov": 40)";
    std::string text = kScene;
    text.replace(text.find(original), original.size(), camera);
    const std::string oblique = test::writeTemp("oblique.json", text);
    ASSERT_EQ(runGlint("render " + oblique + " --quiet -o " + tmp("oblique.exr")).exitCode, 0);
    const OIIO::ImageSpec o = specOf(tmp("oblique.exr"));
    const Scene loaded = test::sceneFromText(text);
    const Camera cam(loaded.cameraDesc, 48, 32);
    for (const auto& [x, y] : {std::pair{0, 0}, {48, 0}, {0, 32}, {48, 32}, {12, 20}}) {
      const Ray ray = cam.generateRay(float(x), float(y));
      // The camera works in render space, world − worldOrigin (io/placement.h).
      const Vec3f pRender = ray.o + 3.0f * ray.d;
      const Vec3d p = Vec3d{pRender.x, pRender.y, pRender.z} + loaded.worldOrigin;
      const Vec3d ndc = throughExrMatrix(o, "worldToNDC", p);
      EXPECT_NEAR(ndc.x, x / 48.0, 1e-5) << camera << " pixel " << x << "," << y;
      EXPECT_NEAR(ndc.y, y / 32.0, 1e-5) << camera << " pixel " << x << "," << y;
      // In front of the camera, at the point's distance along the view axis.
      const Vec3d inCamera = throughExrMatrix(o, "worldToCamera", p);
      EXPECT_NEAR(inCamera.z, 3.0 * dot(ray.d, -cam.w()), 1e-5);
    }
  }
}

// Runs `glint ARGS` in the background, sends `signal` once `ready` (a shell condition over
// $pid and $log, the process's stderr) holds, and returns the exit status and stderr. The signal
// is sent once: a second one ends the process at once (core/interrupt.h).
struct Interrupted {
  int exitCode;
  std::string log;
};
Interrupted interruptWhen(const std::string& args, const std::string& ready,
                          const std::string& signal, const std::string& logName) {
  const std::string log = tmp(logName);
  const std::string cmd = "bash -c 'log=" + log + "; " + std::string(GLINT_BINARY) + " " + args +
                          " 2>$log & pid=$!; for i in $(seq 600); do " + ready +
                          " && break; sleep 0.1; done; kill -" + signal +
                          " $pid; wait $pid; exit $?' >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return {WEXITSTATUS(status), test::readFile(log)};
}

// Under way: the render said it is rendering, which it does once a signal no longer ends the
// process but stops the render (core/interrupt.h).
const std::string kRendering = "grep -qs rendering $log";
// Some pixels done: the first progress line (a tenth of the frame).
const std::string kTenthDone = "grep -qs % $log";

TEST(Output, InterruptedRenderLeavesAValidPartialExr) {
  // A render of several seconds interrupted once under way: exit 130 (CLI.md), an EXR that reads
  // back, marked glint:partial = 1. A tenth of the way in, the passes to 8, 16, ... spp have
  // finished everywhere, so every pixel keeps them: all rendered (alpha 1, the background is
  // opaque), with fewer samples than asked, and the finished passes in glint:passes.
  const std::string scene = test::writeTemp("slow.json", kScene);
  const std::string out = tmp("partial.exr");
  const Interrupted run =
      interruptWhen("render " + scene + " --spp 4096 --width 96 --height 64 --threads 1 -o " + out,
                    kTenthDone, "INT", "partial.log");
  ASSERT_EQ(run.exitCode, 130) << run.log;
  const OIIO::ImageSpec s = specOf(out);
  EXPECT_EQ(s.get_int_attribute("glint:partial", -1), 1);
  const int fewest = s.get_int_attribute("glint:min_pixel_spp", -1);
  EXPECT_GE(fewest, 8);
  EXPECT_LT(fewest, 4096);
  EXPECT_NE(s.get_string_attribute("glint:passes").find("\"spp\":" + std::to_string(fewest)),
            std::string::npos)
      << s.get_string_attribute("glint:passes");
  const Image img = readImage(out);  // RGBA, then the resume state's channels
  const auto stride = size_t(img.channels);
  for (size_t i = 3; i < img.pixels.size(); i += stride)
    ASSERT_EQ(img.pixels[i], 1.0f) << i / stride;
}

TEST(Output, AnInterruptStopsAOnePixelFrameAtAnySampleCount) {
  // One pixel of 2^28 samples is one tile, so only a cancel polled within tiles stops it
  // (between tiles it would run to the end: rc 0, a complete frame). Polled between chunks of
  // 64 samples, SIGTERM stops it mid-pass: exit 130, a partial EXR whose pixel keeps the
  // passes it finished.
  const std::string out = tmp("one_pixel.exr");
  const Interrupted run =
      interruptWhen("render --width 1 --height 1 --spp 268435456 --threads 1 -o " + out, kRendering,
                    "TERM", "one_pixel.log");
  ASSERT_EQ(run.exitCode, 130) << run.log;
  EXPECT_NE(run.log.find("wrote the partial frame"), std::string::npos) << run.log;
  EXPECT_EQ(specOf(out).get_int_attribute("glint:partial", -1), 1);
  // The signal may come before the first pass (8 samples) is done: then the pixel is
  // unrendered, alpha 0.
  const int taken = specOf(out).get_int_attribute("glint:max_pixel_spp", -1);
  EXPECT_GE(taken, 0);
  EXPECT_LT(taken, 268435456);
  EXPECT_EQ(readImage(out).pixels[3], taken > 0 ? 1.0f : 0.0f);  // alpha, the 4th channel
}

TEST(Output, AnInterruptedRenderToADisplayImageWritesNone) {
  // A PNG cannot say it is partial or carry the state to resume it: an interrupted render to
  // -o frame.png writes no frame (exit 130, and says so) rather than an unmarked partial one.
  const std::string out = tmp("interrupted.png");
  fs::remove(out);
  const Interrupted run =
      interruptWhen("render --width 1 --height 1 --spp 268435456 --threads 1 -o " + out, kRendering,
                    "TERM", "interrupted_png.log");
  ASSERT_EQ(run.exitCode, 130) << run.log;
  EXPECT_NE(run.log.find(out + " not written"), std::string::npos) << run.log;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Output, AnInterruptWhileLoadingEndsAtOnceWithExit130) {
  // The scene is a FIFO whose writer (this test, which holds it open) never writes, so loading
  // waits for ever: SIGTERM there (once /proc shows the handler installed: SigCgt bit 14 is
  // SIGTERM) must end the process with 130 and say so, not 143 in silence, and write nothing.
  // (A FIFO with no writer at all is not waited for: it reads as empty, core/input_files.h.)
  const std::string fifo = tmp("never_written.json");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int writer = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);  // Linux: opens without a reader
  ASSERT_GE(writer, 0);
  const std::string out = tmp("never.exr");
  const std::string handlerInstalled =
      "(( 0x$(grep SigCgt /proc/$pid/status | cut -f2) & 0x4000 ))";
  const Interrupted run =
      interruptWhen("render " + fifo + " -o " + out, handlerInstalled, "TERM", "loading.log");
  EXPECT_EQ(run.exitCode, 130) << run.log;
  EXPECT_NE(run.log.find("terminated (SIGTERM)"), std::string::npos) << run.log;
  EXPECT_FALSE(fs::exists(out));
  ::close(writer);
  fs::remove(fifo);
}

TEST(Output, CropsMergeIntoTheFullFrameByteForByte) {
  const std::string scene = test::writeTemp("merge.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + tmp("full.exr")).exitCode, 0);
  // Three crops of different shapes, thread counts, tile sizes and orders.
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 0 20 0 32 -o " + tmp("c1.exr")).exitCode,
            0);
  ASSERT_EQ(runGlint("render " + scene +
                     " --quiet --crop 20 48 0 13 --threads 1 --tile-order row -o " + tmp("c2.exr"))
                .exitCode,
            0);
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --crop 20 48 13 32 --tile-size 5 -o " + tmp("c3.exr"))
          .exitCode,
      0);
  const auto merge = [](const std::string& args) { return runGlint("merge " + args); };
  ASSERT_EQ(merge(tmp("m.exr") + " " + tmp("c1.exr") + " " + tmp("c2.exr") + " " + tmp("c3.exr"))
                .exitCode,
            0);
  EXPECT_EQ(readImage(tmp("m.exr")).pixels, readImage(tmp("full.exr")).pixels);
  // The merged frame's estimated errors are the crops' weighted by their pixels (20 × 32,
  // 28 × 13 and 28 × 19 of 48 × 32), not the first crop's alone; its passes, each crop's own,
  // are left out.
  const OIIO::ImageSpec merged = specOf(tmp("m.exr"));
  double mse = 0, relmse = 0;
  const std::pair<const char*, double> crops[3] = {
      {"c1.exr", 20 * 32}, {"c2.exr", 28 * 13}, {"c3.exr", 28 * 19}};
  for (const auto& [name, pixels] : crops) {
    const OIIO::ImageSpec c = specOf(tmp(name));
    mse += pixels * std::pow(c.get_float_attribute("glint:estimated_rmse"), 2);
    relmse += pixels * c.get_float_attribute("glint:estimated_relmse");
    EXPECT_EQ(c.get_int_attribute("glint:min_pixel_spp"), 4) << name;
  }
  EXPECT_NEAR(merged.get_float_attribute("glint:estimated_rmse"), std::sqrt(mse / (48 * 32)),
              1e-6 * std::sqrt(mse / (48 * 32)));
  EXPECT_NEAR(merged.get_float_attribute("glint:estimated_relmse"), relmse / (48 * 32),
              1e-6 * relmse / (48 * 32));
  EXPECT_EQ(merged.get_int_attribute("glint:min_pixel_spp"), 4);
  EXPECT_EQ(merged.get_int_attribute("glint:max_pixel_spp"), 4);
  EXPECT_EQ(merged.find_attribute("glint:passes"), nullptr);

  // A hole is named as the crop that fills it.
  const auto hole = merge(tmp("h.exr") + " " + tmp("c1.exr") + " " + tmp("c3.exr"));
  EXPECT_EQ(hole.exitCode, 2);
  EXPECT_NE(hole.output.find("--crop 20 48 0 13"), std::string::npos) << hole.output;
  EXPECT_FALSE(fs::exists(tmp("h.exr")));
  // Overlaps and other settings are refused.
  const auto overlap = merge(tmp("o.exr") + " " + tmp("c1.exr") + " " + tmp("full.exr"));
  EXPECT_EQ(overlap.exitCode, 2);
  EXPECT_NE(overlap.output.find("overlap at pixel (0, 0)"), std::string::npos) << overlap.output;
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --seed 6 --crop 20 48 13 32 -o " + tmp("other.exr"))
          .exitCode,
      0);
  const auto other =
      merge(tmp("x.exr") + " " + tmp("c1.exr") + " " + tmp("c2.exr") + " " + tmp("other.exr"));
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_NE(other.output.find("different scene or settings"), std::string::npos) << other.output;
}

TEST(Output, MergedResumableCropsLeaveTheirResumeStatesOut) {
  // Each crop's state was copied with the first crop's checksum: --resume of the merged frame
  // called it altered. The state is left out with a warning; resuming the frame says it holds
  // none, and its pixels are the crops'.
  const std::string scene = test::writeTemp("merge-resumable.json", kScene);
  const std::string left = tmp("resumable-left.exr"), right = tmp("resumable-right.exr");
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --resumable --crop 0 20 0 32 -o " + left).exitCode, 0);
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --resumable --crop 20 48 0 32 -o " + right).exitCode,
      0);
  const std::string merged = tmp("resumable-merged.exr");
  const auto m = runGlint("merge " + merged + " " + left + " " + right);
  EXPECT_EQ(m.exitCode, 0) << m.output;
  EXPECT_NE(m.output.find("the crops' resume states are left out of " + merged), std::string::npos)
      << m.output;
  const OIIO::ImageSpec spec = specOf(merged);
  EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(spec.find_attribute("glint:resume_checksum"), nullptr);
  const auto resumed =
      runGlint("render " + scene + " --quiet --spp 8 --resume " + merged + " -o " + tmp("r.exr"));
  EXPECT_EQ(resumed.exitCode, 2) << resumed.output;
  EXPECT_NE(resumed.output.find("holds no resume state"), std::string::npos) << resumed.output;
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --resumable -o " + tmp("resumable-full.exr")).exitCode,
      0);
  const auto rgbaOf = [](const Image& image) {
    std::vector<float> rgba;
    for (size_t p = 0; p < image.pixels.size(); p += size_t(image.channels))
      rgba.insert(rgba.end(), image.pixels.begin() + long(p), image.pixels.begin() + long(p) + 4);
    return rgba;
  };
  EXPECT_EQ(readImage(merged).pixels, rgbaOf(readImage(tmp("resumable-full.exr"))));
}

TEST(Output, CompareRefusesCropsThatLieApart) {
  // Two 16 x 14 crops of one frame at other places were compared pixel by pixel (exit 0):
  // different pixels of the scene, not two renders of the same ones.
  const std::string scene = test::writeTemp("compare-crops.json", kScene);
  const std::string a = tmp("crop-a.exr"), b = tmp("crop-b.exr");
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 4 20 3 17 -o " + a).exitCode, 0);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 0 16 0 14 -o " + b).exitCode, 0);
  const auto apart = runGlint("compare " + a + " " + b);
  EXPECT_EQ(apart.exitCode, 2) << apart.output;
  EXPECT_NE(apart.output.find("images cover other pixels: 16x14: " + a +
                              " at (4, 3) of a 48x32 frame, " + b + " at (0, 0) of a 48x32 frame"),
            std::string::npos)
      << apart.output;
  const auto same = runGlint("compare " + a + " " + a);
  EXPECT_EQ(same.exitCode, 0) << same.output;
  // In frames of other sizes they may be the same pixels (a reference another tool cut out):
  // compared, with a warning that says how.
  const std::string big = tmp("crop-big.exr");
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --width 96 --height 64 --crop 0 16 0 14 -o " + big)
          .exitCode,
      0);
  const auto sizes = runGlint("compare " + big + " " + b);
  EXPECT_EQ(sizes.exitCode, 0) << sizes.output;
  EXPECT_NE(sizes.output.find("the images lie in frames of other sizes, 16x14: " + big +
                              " at (0, 0) of a 96x64 frame, " + b +
                              " at (0, 0) of a 48x32 frame: compared pixel for pixel"),
            std::string::npos)
      << sizes.output;
  // Of other sizes, they are refused naming both files and their sizes.
  ASSERT_EQ(runGlint("render " + scene + " --quiet --width 20 --height 10 -o " + tmp("small.exr"))
                .exitCode,
            0);
  const auto sizeApart = runGlint("compare " + a + " " + tmp("small.exr"));
  EXPECT_EQ(sizeApart.exitCode, 2) << sizeApart.output;
  EXPECT_NE(sizeApart.output.find("images differ in size: " + a + " is 16x14, " + tmp("small.exr") +
                                  " 20x10"),
            std::string::npos)
      << sizeApart.output;
}

TEST(Output, MergeRefusesACropWhoseChannelsWereRenamed) {
  // The second crop rewritten with its alpha named "Y", all else (its settings hash too) kept:
  // the same pixel types in OpenEXR's sorted order (B, G, R, Y against A, B, G, R), which merge
  // once took for the same channels and copied byte for byte, B into A. Refused, naming both
  // channel lists, and no frame written.
  const std::string scene = test::writeTemp("merge-renamed.json", kScene);
  const std::string left = tmp("renamed-left.exr"), right = tmp("renamed-right.exr");
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 0 20 0 32 -o " + left).exitCode, 0);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --crop 20 48 0 32 -o " + right).exitCode, 0);
  const std::string renamed = tmp("renamed-alpha.exr");
  {
    auto in = OIIO::ImageInput::open(right);
    ASSERT_TRUE(in);
    OIIO::ImageSpec spec = in->spec();
    std::vector<float> pixels(spec.image_pixels() * size_t(spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
    spec.channelnames[3] = "Y";
    spec.alpha_channel = -1;
    auto out = OIIO::ImageOutput::create(renamed);
    ASSERT_TRUE(out && out->open(renamed, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(out->close());
  }
  EXPECT_EQ(specOf(renamed).get_string_attribute("glint:settings_hash"),
            specOf(left).get_string_attribute("glint:settings_hash"));
  const std::string merged = tmp("renamed-merged.exr");
  const auto r = runGlint("merge " + merged + " " + left + " " + renamed);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(renamed + " has other channels or pixel types than " + left),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("\"Y\""), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(merged));
  // The crops as rendered still merge.
  EXPECT_EQ(runGlint("merge " + merged + " " + left + " " + right).exitCode, 0);
}

TEST(Output, SeveralCropsOfOneRunEqualTheirSeparateRenders) {
  // One process, one scene load, three --crop with an -o each (what a farm task of several
  // tiles runs): each crop holds the same bytes as its own run, so they merge into the frame.
  const std::string scene = test::writeTemp("crops.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + tmp("crops-full.exr")).exitCode, 0);
  const auto run = runGlint("render " + scene + " --quiet --crop 0 20 0 32 -o " + tmp("k1.exr") +
                            " --crop 20 48 0 13 -o " + tmp("k2.exr") + " --crop 20 48 13 32 -o " +
                            tmp("k3.exr"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  ASSERT_EQ(
      runGlint("render " + scene + " --quiet --crop 20 48 0 13 -o " + tmp("k2-alone.exr")).exitCode,
      0);
  EXPECT_EQ(readImage(tmp("k2.exr")).pixels, readImage(tmp("k2-alone.exr")).pixels);
  EXPECT_EQ(specOf(tmp("k2.exr")).get_string_attribute("glint:crop"), "20 48 0 13");
  ASSERT_EQ(runGlint("merge " + tmp("k.exr") + " " + tmp("k1.exr") + " " + tmp("k2.exr") + " " +
                     tmp("k3.exr"))
                .exitCode,
            0);
  EXPECT_EQ(readImage(tmp("k.exr")).pixels, readImage(tmp("crops-full.exr")).pixels);

  // Each crop needs its own output, and the outputs that describe one frame take one crop.
  const auto fewer =
      runGlint("render " + scene + " --crop 0 8 0 8 --crop 8 16 0 8 -o " + tmp("only-one.exr"));
  EXPECT_EQ(fewer.exitCode, 2);
  EXPECT_NE(fewer.output.find("2 --crop need one -o each"), std::string::npos) << fewer.output;
  const auto same = runGlint("render " + scene + " --crop 0 8 0 8 -o " + tmp("s.exr") +
                             " --crop 8 16 0 8 -o " + tmp("s.exr"));
  EXPECT_EQ(same.exitCode, 2);
  EXPECT_NE(same.output.find("-o " + tmp("s.exr") + " and -o " + tmp("s.exr") + " name one file"),
            std::string::npos)
      << same.output;
  const auto display =
      runGlint("render " + scene + " --crop 0 8 0 8 -o " + tmp("d1.exr") + " --crop 8 16 0 8 -o " +
               tmp("d2.exr") + " --display " + tmp("d.png"));
  EXPECT_EQ(display.exitCode, 2);
  EXPECT_FALSE(fs::exists(tmp("d1.exr")));
}

TEST(Output, MissingRegionsAreDisjointRectangles) {
  // 4 × 3 frame, covered except an L: column 3 (all rows) and row 2 (columns 0–2).
  std::vector<bool> covered(12, true);
  for (int y = 0; y < 3; ++y) covered[size_t(y) * 4 + 3] = false;
  for (int x = 0; x < 3; ++x) covered[8 + size_t(x)] = false;
  const auto regions = missingRegions(covered, 4, 3);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].x0, 3);  // the column, found first in row order
  EXPECT_EQ(regions[0].y1, 3);
  EXPECT_EQ(regions[1].x0, 0);
  EXPECT_EQ(regions[1].x1, 3);
  EXPECT_EQ(regions[1].y0, 2);
}

}  // namespace
}  // namespace glint
