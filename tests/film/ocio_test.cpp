// Display images through OpenColorIO and the bundled config (ocio/config.ocio).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "film/display.h"
#include "test_util.h"

namespace glint {
namespace {

std::vector<float> through(const DisplaySettings& s, std::vector<float> rgb) {
  DisplayTransform(s).apply(rgb.data(), int(rgb.size() / 3), 1, 3);
  return rgb;
}

TEST(Ocio, BundledConfigPassesOciocheck) {
  const std::string cmd =
      "ociocheck --iconfig " + std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}

TEST(Ocio, StandardViewIsTheSrgbEncoding) {
  // sRGB OETF: 0.18 → 1.055·0.18^(1/2.4) − 0.055 = 0.4614 → code 117.7, so 118 ± 1 (the
  // Rec.709 → AP0 → XYZ → sRGB matrices round-trip to about 1e-6); 1.0 → 255; 0 → 0.
  DisplaySettings standard;
  standard.view = "Standard";
  const std::vector<float> out = through(standard, {0.18f, 0.18f, 0.18f, 1, 1, 1, 0, 0, 0});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(255 * out[size_t(c)], 118, 1) << c;
  for (int c = 3; c < 6; ++c) EXPECT_NEAR(255 * out[size_t(c)], 255, 0.5) << c;
  for (int c = 6; c < 9; ++c) EXPECT_NEAR(out[size_t(c)], 0, 1e-6) << c;
}

TEST(Ocio, RawIsTheIdentity) {
  DisplaySettings raw;
  raw.view = "Raw";
  const std::vector<float> in = {0.3f, 0.5f, 2.0f, -1, 0, 1e6f};
  EXPECT_EQ(through(raw, in), in);
}

TEST(Ocio, AcesViewTonemapsHighlights) {
  // The ACES SDR rendering compresses highlights instead of clipping them: scene values 0.18,
  // 1, 4 and 16 (grey) map to strictly increasing display values, all below 1.0, where the
  // Standard view applies the sRGB encoding alone, 16 → 1.055·16^(1/2.4) − 0.055 = 3.2946 (the
  // display image then clips it to 1).
  DisplaySettings aces;
  aces.view = "ACES 1.0 - SDR Video";
  const std::vector<float> out = through(aces, {0.18f, 0.18f, 0.18f, 1, 1, 1, 4, 4, 4, 16, 16, 16});
  for (int i = 0; i < 3; ++i) EXPECT_LT(out[size_t(3 * i)], out[size_t(3 * i + 3)]) << i;
  EXPECT_LT(out[9], 1.0f);
  DisplaySettings standardView;
  standardView.view = "Standard";
  const std::vector<float> standard = through(standardView, {16, 16, 16});
  for (float v : standard) EXPECT_NEAR(v, 1.055 * std::pow(16.0, 1 / 2.4) - 0.055, 1e-3);
}

double srgbEncode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

TEST(Ocio, EveryDisplayDefaultsToTheToneMappedView) {
  // sRGB, Rec.1886 and Display P3 all open on the ACES SDR rendering: a scene value of 16
  // stays below display white instead of clipping.
  for (const char* display : {"sRGB", "Rec.1886", "Display P3"}) {
    DisplaySettings s;
    s.display = display;
    const std::vector<float> out = through(s, {16, 16, 16});
    EXPECT_LT(out[0], 1.0f) << display;
    EXPECT_GT(out[0], 0.8f) << display;
  }
}

TEST(Ocio, Rec1886AndDisplayP3Encodings) {
  // Standard view. Rec.1886 with a black level of 0 is the pure 2.4 power: 0.18 → 0.18^(1/2.4)
  // = 0.48944. Display P3 is P3-D65 primaries with the sRGB curve: Rec.709 red (1, 0, 0) is
  // (0.82246, 0.03319, 0.01708) in linear P3-D65 (the 709 → P3 matrix's first column), then
  // encoded. Tolerance 2e-3: the config goes through ACES AP0 with Bradford adaptations to D60
  // and back, exact to about 1e-4 in linear light, which the curve's slope near 0 magnifies.
  DisplaySettings rec1886;
  rec1886.display = "Rec.1886";
  rec1886.view = "Standard";
  for (float v : through(rec1886, {0.18f, 0.18f, 0.18f}))
    EXPECT_NEAR(v, std::pow(0.18, 1 / 2.4), 2e-3);
  DisplaySettings p3;
  p3.display = "Display P3";
  p3.view = "Standard";
  const std::vector<float> red = through(p3, {1, 0, 0});
  EXPECT_NEAR(red[0], srgbEncode(0.82246), 2e-3);
  EXPECT_NEAR(red[1], srgbEncode(0.03319), 2e-3);
  EXPECT_NEAR(red[2], srgbEncode(0.01708), 2e-3);
}

TEST(Ocio, AStudioConfigShowsARec709FrameAsTheBundledOneDoes) {
  // A studio config whose scene_linear is ACEScg and which has no lin_rec709: Glint's frame
  // (glint:colorspace lin_rec709) must reach its display through the interchange role, not be
  // taken as ACEScg, which showed saturated colours up to 0.33 off.
  std::string text = [] {
    std::ifstream f(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  const size_t begin = text.find("  - !<ColorSpace>\n    name: lin_rec709");
  const size_t end = text.find("  - !<ColorSpace>", begin + 1);
  ASSERT_NE(begin, std::string::npos);
  text.erase(begin, end - begin);
  for (size_t at; (at = text.find(": lin_rec709")) != std::string::npos;)
    text.replace(at, 12, ": ACEScg");
  const std::string studio = test::writeTemp("studio.ocio", text);
  const std::vector<float> saturated = {0.8f, 0.1f, 0.02f, 0.05f, 0.4f, 0.9f};
  DisplaySettings bundled;
  bundled.view = "Standard";
  DisplaySettings viaStudio = bundled;
  viaStudio.configPath = studio;
  const std::vector<float> expected = through(bundled, saturated);
  const std::vector<float> got = through(viaStudio, saturated);
  // The same matrices composed in another order: float rounding only.
  for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-4) << i;
  // The old way, the frame read as the config's scene_linear, is far off: the test can fail.
  DisplaySettings asSceneLinear = viaStudio;
  asSceneLinear.source = "";
  const std::vector<float> wrong = through(asSceneLinear, saturated);
  double worst = 0;
  for (size_t i = 0; i < wrong.size(); ++i)
    worst = std::max(worst, std::abs(double(wrong[i]) - expected[i]));
  EXPECT_GT(worst, 0.1);

  // glint convert takes the colour space from the frame's glint:colorspace.
  const auto path = [](const char* n) { return (test::tempDir() / n).string(); };
  const std::string scene = test::writeTemp("saturated.json", R"({
    "render": {"width": 2, "height": 2, "spp": 1, "background": [0.8, 0.1, 0.02]},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "objects": []})");
  ASSERT_EQ(test::runGlint("render --quiet " + scene + " -o " + path("saturated.exr")).exitCode, 0);
  ASSERT_EQ(
      test::runGlint("convert --view Standard " + path("saturated.exr") + " " + path("bundled.tif"))
          .exitCode,
      0);
  ASSERT_EQ(test::runGlint("convert --view Standard --ocio-config " + studio + " " +
                           path("saturated.exr") + " " + path("studio.tif"))
                .exitCode,
            0);
  const auto firstPixel = [](const std::string& p) {
    auto in = OIIO::ImageInput::open(p);
    std::vector<float> v(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
    in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, v.data());
    return std::vector<float>(v.begin(), v.begin() + 3);
  };
  const std::vector<float> a = firstPixel(path("bundled.tif")), b = firstPixel(path("studio.tif"));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[size_t(c)], b[size_t(c)], 2.0 / 65535) << c;  // 16-bit
}

TEST(Ocio, EnvironmentConfigIsUsedAndBadConfigsAreNamed) {
  // A config in $OCIO wins over the bundled one (here a copy of it, whose source we can see).
  const std::string copy = test::writeTemp("env.ocio", [] {
    std::ifstream f(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
    return std::string(std::istreambuf_iterator<char>(f), {});
  }());
  ::setenv("OCIO", copy.c_str(), 1);
  EXPECT_EQ(DisplayTransform({}).configSource(), "$OCIO = " + copy);
  ::setenv("OCIO", "/no/such/config.ocio", 1);
  try {
    DisplayTransform t({});
    ADD_FAILURE() << "a missing $OCIO config was accepted";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/config.ocio"), std::string::npos) << e.what();
  }
  ::unsetenv("OCIO");
  EXPECT_EQ(DisplayTransform({}).configSource(), "bundled (ocio/config.ocio)");
  DisplaySettings badView;
  badView.view = "Filmic";
  try {
    DisplayTransform t(badView);
    ADD_FAILURE() << "an unknown view was accepted";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find("Filmic"), std::string::npos) << e.what();
  }
  const auto r = test::runGlint("render --quiet --width 8 --height 8 --spp 1 -o " +
                                (test::tempDir() / "o.exr").string() + " --display " +
                                (test::tempDir() / "o.png").string() + " --ocio-config /nope.ocio");
  EXPECT_EQ(r.exitCode, 2);  // a usage error (CLI.md), found before rendering
  EXPECT_NE(r.output.find("OCIO config not found: /nope.ocio"), std::string::npos) << r.output;
  // An unknown view or look likewise: exit 2, and no frame written.
  for (const std::string bad : {"--view Filmic", "--look NoSuchLook", "--ocio-display Nope"}) {
    const std::string exr = (test::tempDir() / "never.exr").string();
    const auto u =
        test::runGlint("render --quiet --width 8 --height 8 --spp 1 -o " + exr + " --display " +
                       (test::tempDir() / "never.png").string() + " " + bad);
    EXPECT_EQ(u.exitCode, 2) << bad << ": " << u.output;
    EXPECT_FALSE(std::filesystem::exists(exr)) << bad;
  }
}

TEST(Ocio, ConvertDevelopsTheSameImageAsRender) {
  const auto path = [](const char* n) { return (test::tempDir() / n).string(); };
  ASSERT_EQ(test::runGlint("render --quiet --width 40 --height 24 --spp 1 -o " + path("c.exr") +
                           " --display " + path("render.png"))
                .exitCode,
            0);
  ASSERT_EQ(test::runGlint("convert " + path("c.exr") + " " + path("convert.png")).exitCode, 0);
  ASSERT_EQ(test::runGlint("convert " + path("c.exr") + " " + path("convert.tif")).exitCode, 0);
  const auto pixels = [](const std::string& p, OIIO::TypeDesc type) {
    auto in = OIIO::ImageInput::open(p);
    std::vector<float> v(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
    in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, v.data());
    EXPECT_EQ(in->spec().format, type) << p;
    return v;
  };
  EXPECT_EQ(pixels(path("convert.png"), OIIO::TypeDesc::UINT8),
            pixels(path("render.png"), OIIO::TypeDesc::UINT8));
  EXPECT_EQ(pixels(path("convert.tif"), OIIO::TypeDesc::UINT16).size(), size_t(40 * 24 * 3));
}

TEST(Ocio, OiiotoolDevelopsTheSameDisplayImageAsConvert) {
  // A real compositing tool on Glint's frame: oiiotool --ociodisplay with the bundled config
  // (which calls lin_rec709 "Linear" too, OIIO's name for an EXR's space) must give the same
  // 8-bit pixels as glint convert, in both views.
  const auto path = [](const char* n) { return (test::tempDir() / n).string(); };
  ASSERT_EQ(test::runGlint("render --quiet --width 80 --height 50 --spp 2 -o " + path("tool.exr"))
                .exitCode,
            0);
  for (const std::string view : {"Standard", "ACES 1.0 - SDR Video"}) {
    ASSERT_EQ(test::runGlint("convert --view \"" + view + "\" " + path("tool.exr") + " " +
                             path("glint.png"))
                  .exitCode,
              0);
    const std::string oiiotool = "oiiotool --colorconfig " + std::string(GLINT_SOURCE_DIR) +
                                 "/ocio/config.ocio " + path("tool.exr") +
                                 " --ociodisplay sRGB \"" + view + "\" --ch R,G,B -d uint8 -o " +
                                 path("oiiotool.png") + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(oiiotool.c_str()), 0) << oiiotool;
    const auto pixels = [](const std::string& p) {
      auto in = OIIO::ImageInput::open(p);
      std::vector<unsigned char> v(size_t(in->spec().image_pixels()) * 3);
      in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, v.data());
      return v;
    };
    EXPECT_EQ(pixels(path("glint.png")), pixels(path("oiiotool.png"))) << view;
  }
}

// The bundled config in `dir` (as look.ocio) with `looks` (YAML) appended, its search path the
// config's own folder.
std::string bundledConfigWith(const std::filesystem::path& dir, const std::string& looks) {
  std::string text = [] {
    std::ifstream f(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  text.replace(text.find("search_path: \"\""), 15, "search_path: \".\"");
  const std::filesystem::path config = dir / "look.ocio";
  std::ofstream(config) << text << "\nlooks:\n" << looks;
  return config.string();
}

// The bundled config in `dir` with a look "grade" whose FileTransform reads `lut` (resolved
// through the config's search path).
std::string configWithLook(const std::filesystem::path& dir, const std::string& lut) {
  return bundledConfigWith(dir,
                           "  - !<Look>\n    name: grade\n    process_space: lin_rec709\n"
                           "    transform: !<FileTransform> {src: " +
                               lut + ", interpolation: linear}\n");
}

std::string displayRefusal(const DisplaySettings& s) {
  try {
    DisplayTransform t(s);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Ocio, EveryFileAConfigReadsIsCheckedBeforeOcioOpensIt) {
  // OCIO reads a look's LUT whole when it builds the processor: a FIFO there waited for a
  // writer for ever, /dev/zero was read until 2.1 GB. Each is refused first, naming the look
  // and the file; alarm() ends the test binary if a check ever opens the FIFO.
  ::alarm(20);
  const std::filesystem::path dir = test::tempDir() / "ocio-files";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // A 1D LUT that halves every channel: the look is applied (0.8 → 0.4 through the Raw view,
  // linear interpolation between the LUT's two points, float rounding only).
  std::ofstream(dir / "half.cube") << "LUT_1D_SIZE 2\n0 0 0\n0.5 0.5 0.5\n";
  DisplaySettings s;
  s.view = "Raw";
  s.look = "grade";
  s.configPath = configWithLook(dir, "half.cube");
  const std::vector<float> graded = through(s, {0.8f, 0.2f, 0.6f});
  EXPECT_NEAR(graded[0], 0.4f, 1e-6);
  EXPECT_NEAR(graded[1], 0.1f, 1e-6);
  EXPECT_NEAR(graded[2], 0.3f, 1e-6);
  ASSERT_EQ(::mkfifo((dir / "fifo.cube").c_str(), 0600), 0);
  s.configPath = configWithLook(dir, "fifo.cube");
  const std::string fifo = displayRefusal(s);
  EXPECT_NE(fifo.find("look \"grade\": its FileTransform's file " + (dir / "fifo.cube").string() +
                      " is a FIFO; it must be a regular file"),
            std::string::npos)
      << fifo;
  s.configPath = configWithLook(dir, "/dev/zero");
  EXPECT_NE(displayRefusal(s).find("/dev/zero is a character device"), std::string::npos);
  // The whole config is checked, the look unused too: a display without it is refused as well.
  s.look = "";
  s.configPath = configWithLook(dir, "fifo.cube");
  EXPECT_NE(displayRefusal(s).find("is a FIFO"), std::string::npos);
  // And the config itself.
  s.configPath = (dir / "fifo.cube").string();
  EXPECT_EQ(displayRefusal(s),
            "OCIO config " + s.configPath + " is a FIFO; it must be a regular file");
  ::alarm(0);
  std::filesystem::remove_all(dir);
}

TEST(Ocio, ALooksGainIsHeldToTheCeilingTheViewIsGiven) {
  // The pixels reach the view clamped to ±65504, but a look applied after that clamp passed a
  // gain of 1e25 on to ACES's curve, which made NaN: a black PNG. Past the look they are
  // clamped again, so the channel the look raises shows as the brightest the view gives.
  const std::filesystem::path dir = test::tempDir() / "ocio-gain";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  DisplaySettings s;
  s.look = "gain";
  s.configPath = bundledConfigWith(
      dir,
      "  - !<Look>\n    name: gain\n    process_space: lin_rec709\n    transform: "
      "!<MatrixTransform> {matrix: [1e25, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}\n");
  const std::vector<float> shown = through(s, {1, 0.18f, 0.18f});
  s.look = "";
  const std::vector<float> brightest = through(s, {65504, 0.18f, 0.18f});
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(std::isfinite(shown[size_t(c)])) << c;
    EXPECT_EQ(shown[size_t(c)], brightest[size_t(c)]) << c;  // the same clamped input
  }
  EXPECT_GT(shown[0], 0.5f);
  std::filesystem::remove_all(dir);
}

TEST(Ocio, ALoopOfReferencesIsRefusedBeforeOcioFollowsIt) {
  // OCIO's processor builder follows a look that applies itself, or a colour space converted
  // through itself, until the stack overflows (a segfault). Each loop is refused, named.
  const std::filesystem::path dir = test::tempDir() / "ocio-loops";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto look = [](const std::string& name, const std::string& applies) {
    return "  - !<Look>\n    name: " + name +
           "\n    process_space: lin_rec709\n    transform: !<LookTransform> {src: lin_rec709, "
           "dst: lin_rec709, looks: " +
           applies + "}\n";
  };
  DisplaySettings s;
  s.view = "Raw";
  s.look = "a";
  // A look applying another is no loop: accepted, and the identity through Raw.
  s.configPath = bundledConfigWith(dir, look("a", "+b") + look("b", "-c") + look("c", "\"\""));
  EXPECT_EQ(displayRefusal(s), "(accepted)");
  s.configPath = bundledConfigWith(dir, look("a", "a"));
  EXPECT_EQ(displayRefusal(s), "OCIO (" + s.configPath +
                                   "): look \"a\" → look \"a\": these refer to each other in a "
                                   "loop, which OCIO would follow until its stack overflows");
  // Round three looks, and the whole config: a display that uses none of them is refused too.
  s.look = "";
  s.configPath = bundledConfigWith(dir, look("a", "b") + look("b", "+c, a") + look("c", "a"));
  EXPECT_NE(displayRefusal(s).find("look \"a\" → look \"b\" → "), std::string::npos)
      << displayRefusal(s);
  // A colour space converted through itself, by its alias.
  std::string text = [] {
    std::ifstream f(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  text.replace(text.find("\ncolorspaces:\n") + 14, 0,
               "  - !<ColorSpace>\n    name: selfref\n    aliases: [me]\n"
               "    to_scene_reference: !<ColorSpaceTransform> {src: me, dst: lin_rec709}\n");
  s.configPath = (dir / "space.ocio").string();
  std::ofstream(s.configPath) << text;
  EXPECT_NE(displayRefusal(s).find("colour space \"selfref\" → colour space \"selfref\": these "
                                   "refer to each other in a loop"),
            std::string::npos)
      << displayRefusal(s);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace glint
