// Display images through OpenColorIO and the bundled config (ocio/config.ocio).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdlib>

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
  const std::vector<float> out = through({}, {0.18f, 0.18f, 0.18f, 1, 1, 1, 0, 0, 0});
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
  const std::vector<float> standard = through(DisplaySettings{}, {16, 16, 16});
  for (float v : standard) EXPECT_NEAR(v, 1.055 * std::pow(16.0, 1 / 2.4) - 0.055, 1e-3);
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

}  // namespace
}  // namespace glint
