// Display-referred outputs from the command line: -o's format follows its extension (or the
// command refuses before rendering), display PNGs keep a transparent frame's alpha and carry
// their display's colour tag, convert reads a foreign EXR's colour space, and the help states
// the defaults the code uses. PNGs are read back with libpng.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "film/display.h"
#include "png_util.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

// The default scene, small and quick.
const std::string kSmall = "render --quiet --width 24 --height 16 --spp 1 ";

double srgbEncode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

// A float EXR of one pixel value, with OpenEXR's chromaticities when given (red, green, blue,
// white), through OpenImageIO.
void writeExr(const std::string& path, const std::vector<std::string>& channels,
              const std::vector<float>& pixel, const std::vector<float>& chromaticities = {}) {
  OIIO::ImageSpec spec(2, 2, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  if (!chromaticities.empty())
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8),
                   chromaticities.data());
  std::vector<float> pixels;
  for (int i = 0; i < 4; ++i) pixels.insert(pixels.end(), pixel.begin(), pixel.end());
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  ASSERT_TRUE(out->close());
}

TEST(DisplayOutput, APngNamedOutputIsAPngAndAJpegOneAJpeg) {
  // -o frame.png used to write an OpenEXR file under that name.
  const auto r = runGlint(kSmall + "-o " + tmp("frame.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const test::PngFile png = test::readPng(tmp("frame.png"));
  EXPECT_EQ(png.signature, test::kPngSignature);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.width, 24u);
  EXPECT_EQ(png.height, 16u);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGB);  // an opaque frame
  EXPECT_EQ(png.bitDepth, 8);
  // It is the frame --display develops, byte for byte.
  ASSERT_EQ(
      runGlint(kSmall + "-o " + tmp("frame.exr") + " --display " + tmp("display.png")).exitCode, 0);
  EXPECT_EQ(test::readFile(tmp("frame.png")), test::readFile(tmp("display.png")));
  // JPEG: the SOI marker FF D8 FF; TIFF: "II*\0" (little-endian).
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("frame.jpg")).exitCode, 0);
  EXPECT_EQ(test::readFile(tmp("frame.jpg")).substr(0, 3), "\xff\xd8\xff");
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("frame.tif")).exitCode, 0);
  EXPECT_EQ(test::readFile(tmp("frame.tif")).substr(0, 4), std::string("II*\0", 4));
}

TEST(DisplayOutput, AnExtensionGlintDoesNotWriteIsRefusedBeforeLoading) {
  // The scene does not parse: the refusal comes before it is read, let alone rendered.
  const std::string broken = test::writeTemp("broken.json", "{ not json");
  for (const char* name : {"frame.xyz", "frame", "frame.webp"}) {
    const auto r = runGlint("render --quiet " + broken + " -o " + tmp(name));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("-o " + tmp(name) + ": "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(".exr (the scene-linear frame), or .png, .jpg, .jpeg, .tif or .tiff"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("JSON"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(tmp(name)));
  }
  // --display takes display images only.
  const auto d = runGlint("render --quiet " + broken + " --display " + tmp("d.exr"));
  EXPECT_EQ(d.exitCode, 2) << d.output;
  EXPECT_NE(d.output.find("--display " + tmp("d.exr") + ": names the OpenEXR format"),
            std::string::npos)
      << d.output;
}

TEST(DisplayOutput, WhatOnlyAnExrCarriesIsRefusedWithADisplayOutput) {
  const std::string broken = test::writeTemp("broken2.json", "{ not json");
  for (const char* flag : {"--half", "--multipart", "--aov depth", "--compression zip",
                           "--resumable", "--preview-every 1"}) {
    const auto r = runGlint("render --quiet " + broken + " -o " + tmp("x.png") + " " + flag);
    EXPECT_EQ(r.exitCode, 2) << flag << r.output;
    const std::string name = std::string(flag).substr(0, std::string(flag).find(' '));
    EXPECT_NE(r.output.find("cannot carry what " + name + " asks for"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("-o " + tmp("x.exr") + " --display " + tmp("x.png")), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(tmp("x.png")));
  }
}

TEST(DisplayOutput, ABadViewForADisplayOutputIsRefusedBeforeRendering) {
  // The OCIO settings of a display -o are checked as --display's are, before the render.
  const auto r =
      runGlint("render --width 24 --height 16 --spp 1 -o " + tmp("v.png") + " --view Nonesuch");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("has no view \"Nonesuch\""), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("rendering 24x16"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(tmp("v.png")));
}

TEST(DisplayOutput, OtherCommandsFollowTheSameRule) {
  writeExr(tmp("a.exr"), {"R", "G", "B"}, {0.5f, 0.5f, 0.5f});
  const auto merge = runGlint("merge " + tmp("merged.png") + " " + tmp("a.exr"));
  EXPECT_EQ(merge.exitCode, 2) << merge.output;
  EXPECT_NE(merge.output.find("writes .exr"), std::string::npos) << merge.output;
  EXPECT_FALSE(fs::exists(tmp("merged.png")));
  const auto diff =
      runGlint("compare " + tmp("a.exr") + " " + tmp("a.exr") + " --diff " + tmp("diff.exr"));
  EXPECT_EQ(diff.exitCode, 2) << diff.output;
  EXPECT_FALSE(fs::exists(tmp("diff.exr")));
  const auto convert = runGlint("convert " + tmp("a.exr") + " " + tmp("a.bmp"));
  EXPECT_EQ(convert.exitCode, 2) << convert.output;
  EXPECT_FALSE(fs::exists(tmp("a.bmp")));
  const auto plot = runGlint("converge --plot " + tmp("plot.png") + " --spp 1");
  EXPECT_EQ(plot.exitCode, 2) << plot.output;
  EXPECT_NE(plot.output.find("writes .svg"), std::string::npos) << plot.output;
}

TEST(DisplayOutput, ATransparentFrameGivesAnRgbaPngWithItsAlpha) {
  // Each pixel's PNG alpha is its EXR alpha in 8 bits; the default scene's sky is missed
  // (alpha 0) and its floor covered (255).
  const auto r = runGlint(kSmall + "--transparent-background -o " + tmp("t.exr") + " --display " +
                          tmp("t.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const test::PngFile png = test::readPng(tmp("t.png"));
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGB_ALPHA);
  EXPECT_EQ(png.bitDepth, 8);
  auto in = OIIO::ImageInput::open(tmp("t.exr"));
  ASSERT_TRUE(in);
  std::vector<float> rgba(24 * 16 * 4);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, rgba.data()));
  ASSERT_EQ(png.samples.size(), rgba.size());
  int empty = 0, full = 0;
  for (size_t p = 0; p < 24 * 16; ++p) {
    const float a = rgba[p * 4 + 3];
    EXPECT_EQ(png.samples[p * 4 + 3], std::lround(255 * a)) << p;
    empty += png.samples[p * 4 + 3] == 0;
    full += png.samples[p * 4 + 3] == 255;
    if (a == 0) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(png.samples[p * 4 + size_t(c)], 0) << p;
    }
  }
  EXPECT_GT(empty, 0);
  EXPECT_GT(full, 0);
}

TEST(DisplayOutput, DisplayPngsCarryTheirDisplaysColourChunk) {
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("srgb.png")).exitCode, 0);
  const test::PngFile srgb = test::readPng(tmp("srgb.png"));
  EXPECT_EQ(srgb.srgbIntent, 0);
  EXPECT_FALSE(srgb.cicp);
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("p3.png") + " --ocio-display \"Display P3\"").exitCode,
            0);
  const test::PngFile p3 = test::readPng(tmp("p3.png"));
  EXPECT_FALSE(p3.srgbIntent);
  EXPECT_EQ(p3.cicp, (std::array<int, 4>{12, 13, 0, 1}));  // P3-D65, sRGB curve, RGB, full
}

TEST(DisplayOutput, ADisplayGlintCannotMapGetsNoTagAndAWarning) {
  // The bundled config with its sRGB display and display colour space renamed "Cinema": no
  // name says what it encodes for, so the PNG carries no colour chunk, and the run says so.
  std::string text = test::readFile(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
  const auto replaceAll = [&](const std::string& from, const std::string& to) {
    for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
      text.replace(at, from.size(), to);
  };
  replaceAll("sRGB - Display", "Cinema - Display");
  replaceAll("\n  sRGB:\n", "\n  Cinema:\n");
  replaceAll("active_displays: [sRGB,", "active_displays: [Cinema,");
  const std::string config = test::writeTemp("cinema.ocio", text);
  const auto r = runGlint(kSmall + "-o " + tmp("cinema.png") + " --ocio-config " + config);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("the OCIO display \"Cinema\" is not one Glint knows a PNG colour tag"),
            std::string::npos)
      << r.output;
  const test::PngFile png = test::readPng(tmp("cinema.png"));
  ASSERT_TRUE(png.ok);
  EXPECT_FALSE(png.srgbIntent);
  EXPECT_FALSE(png.cicp);
  EXPECT_FALSE(png.gamma);
  EXPECT_FALSE(png.chrm);
}

TEST(DisplayOutput, ConvertOfAnAp0TaggedExrMatchesTheHandConvertedValue) {
  // An EXR that is not Glint's, with ACES AP0 chromaticities (ACES white) and no
  // glint:colorspace. AP0 (0.3, 0.25, 0.2) to linear Rec.709 by the published ACES2065-1 →
  // Rec.709 matrix (Bradford D60 → D65):
  //   R = 2.52169·0.3 − 1.13413·0.25 − 0.38756·0.2 = 0.39546
  //   G = −0.27648·0.3 + 1.37272·0.25 − 0.09624·0.2 = 0.24099
  //   B = −0.01538·0.3 − 0.15298·0.25 + 1.16835·0.2 = 0.19081
  // then the Standard view's sRGB curve: codes 168.75, 134.67, 120.88 → 169, 135, 121 (±1).
  // Taken as Rec.709, as convert used to, the input would give 149, 137, 124.
  const double m[3][3] = {
      {2.52169, -1.13413, -0.38756}, {-0.27648, 1.37272, -0.09624}, {-0.01538, -0.15298, 1.16835}};
  const double in[3] = {0.3, 0.25, 0.2};
  writeExr(tmp("ap0.exr"), {"R", "G", "B", "A"}, {0.3f, 0.25f, 0.2f, 1.0f},
           {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f});
  const auto r = runGlint("convert --view Standard " + tmp("ap0.exr") + " " + tmp("ap0.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("ACES2065-1"), std::string::npos) << r.output;
  const test::PngFile png = test::readPng(tmp("ap0.png"));
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGB);  // alpha 1 everywhere: opaque
  for (int c = 0; c < 3; ++c) {
    const double linear = m[c][0] * in[0] + m[c][1] * in[1] + m[c][2] * in[2];
    EXPECT_NEAR(png.samples[size_t(c)], 255 * srgbEncode(linear), 1) << c;
  }
  // --input-colorspace overrides the chromaticities: read as Rec.709, the input is its own
  // linear colour, sRGB(0.3) → 149.
  ASSERT_EQ(runGlint("convert --view Standard --input-colorspace lin_rec709 " + tmp("ap0.exr") +
                     " " + tmp("as709.png"))
                .exitCode,
            0);
  EXPECT_NEAR(test::readPng(tmp("as709.png")).samples[0], 255 * srgbEncode(0.3), 1);
}

TEST(DisplayOutput, ConvertRefusesAnExrWithoutRgbAndAnUnknownColourSpace) {
  writeExr(tmp("depth.exr"), {"Z"}, {3.0f});
  const auto r = runGlint("convert " + tmp("depth.exr") + " " + tmp("depth.png"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(tmp("depth.exr") + ": convert needs R, G and B channels; it has Z"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(tmp("depth.png")));
  writeExr(tmp("rgb.exr"), {"R", "G", "B"}, {0.5f, 0.5f, 0.5f});
  const auto u =
      runGlint("convert --input-colorspace Nonesuch " + tmp("rgb.exr") + " " + tmp("u.png"));
  EXPECT_EQ(u.exitCode, 2) << u.output;
  EXPECT_NE(u.output.find("\"Nonesuch\" is not a colour space of the OCIO config; it has: "),
            std::string::npos)
      << u.output;
  EXPECT_NE(u.output.find("ACEScg"), std::string::npos) << u.output;
  EXPECT_FALSE(fs::exists(tmp("u.png")));
}

// The text of `command --help`'s line for `option`.
std::string helpLine(const std::string& command, const std::string& option) {
  const std::string help = runGlint(command + " --help").output;
  const size_t at = help.find("  " + option + " ");
  if (at == std::string::npos) return "";
  // CLI11 puts a long option's type on its own line and the description on the next.
  size_t end = help.find('\n', at);
  if (help.find("(default", at) > end) end = help.find('\n', end + 1);
  return help.substr(at, end - at);
}

// What the help says the default is: the text in "(default X)" or after "is \"".
std::string statedDefault(const std::string& line) {
  std::smatch m;
  if (std::regex_search(line, m, std::regex("bundled config's is \"([^\"]*)\""))) return m[1].str();
  if (std::regex_search(line, m, std::regex("\\(default ([^)]*)\\)"))) return m[1].str();
  return "(none)";
}

TEST(DisplayOutput, HelpStatesTheDefaultsTheCodeUses) {
  // The help said the default view was "Standard"; it is the config's first view. Each stated
  // default is checked against what the command does without the option.
  for (const char* command : {"render", "convert"}) {
    EXPECT_EQ(statedDefault(helpLine(command, "--view")), kBundledDefaultView) << command;
    EXPECT_EQ(statedDefault(helpLine(command, "--ocio-display")), kBundledDefaultDisplay)
        << command;
  }
  const std::string view = statedDefault(helpLine("render", "--view"));
  const std::string display = statedDefault(helpLine("render", "--ocio-display"));
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("plain.png")).exitCode, 0);
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("stated.png") + " --view \"" + view +
                     "\" --ocio-display \"" + display + "\"")
                .exitCode,
            0);
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("standard.png") + " --view Standard").exitCode, 0);
  EXPECT_EQ(test::readFile(tmp("plain.png")), test::readFile(tmp("stated.png")));
  EXPECT_NE(test::readFile(tmp("plain.png")), test::readFile(tmp("standard.png")));

  // EXR compression, backend and integrator: what the frame records without the options.
  ASSERT_EQ(runGlint(kSmall + "-o " + tmp("defaults.exr")).exitCode, 0);
  auto in = OIIO::ImageInput::open(tmp("defaults.exr"));
  ASSERT_TRUE(in);
  EXPECT_EQ(statedDefault(helpLine("render", "--compression")),
            in->spec().get_string_attribute("compression"));
  EXPECT_EQ(statedDefault(helpLine("render", "--accel")),
            in->spec().get_string_attribute("glint:accel"));
  EXPECT_EQ(statedDefault(helpLine("render", "--integrator")),
            in->spec().get_string_attribute("glint:integrator"));

  // compare --threshold: pixels off by 0.015 and 0.005 count as above it at 0.01, not at 0.02;
  // the share without the option equals the share at the stated value.
  OIIO::ImageSpec spec(2, 1, 3, OIIO::TypeDesc::FLOAT);
  const auto write = [&](const std::string& path, const std::vector<float>& px) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close());
  };
  write(tmp("t0.exr"), {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
  write(tmp("t1.exr"), {0.515f, 0.5f, 0.5f, 0.505f, 0.5f, 0.5f});
  const std::string threshold = statedDefault(helpLine("compare", "--threshold"));
  const auto share = [&](const std::string& extra) {
    const std::string out =
        runGlint("compare " + tmp("t1.exr") + " " + tmp("t0.exr") + " --json - " + extra).output;
    std::smatch m;
    std::regex_search(out, m, std::regex("\"share_above_threshold\": ([0-9.e-]+)"));
    return m[1].str();
  };
  EXPECT_EQ(share(""), share("--threshold " + threshold)) << threshold;
  EXPECT_NE(share("--threshold 0.001"), share("--threshold 0.02"));
}

}  // namespace
}  // namespace glint
