// Display images (film/display.h): straight alpha for transparent frames, the colour tag of the
// display in PNGs (film/display_tag.h), and the colour space convert reads an EXR in
// (film/input_colorspace.h). PNGs are read back with libpng.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "film/display.h"
#include "film/display_tag.h"
#include "film/input_colorspace.h"
#include "png_util.h"
#include "test_util.h"

namespace glint {
namespace {

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

double srgbEncode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

DisplaySettings standardView(const char* display = "sRGB") {
  DisplaySettings s;
  s.display = display;
  s.view = "Standard";
  return s;
}

// Three premultiplied pixels: grey 0.18 covering half the pixel, nothing, grey 0.18 opaque.
const std::vector<float> kHalfEmptyFull = {0.09f, 0.09f, 0.09f, 0.5f,  0,     0,
                                           0,     0,     0.18f, 0.18f, 0.18f, 1};

TEST(DisplayImage, ATransparentFrameGivesStraightAlpha) {
  // The half-covered pixel's colour is the grey that covers it, 0.18, developed alone:
  // sRGB(0.18) = 0.46135 → 255·0.46135 = 117.6 → 118 (±1: the view goes through AP0 and back,
  // about 1e-4). Developing the premultiplied 0.09 instead would give sRGB(0.09) → 84.
  // Alpha 0.5 → 127.5 → 128 (rounded half up). The empty pixel is 0 everywhere, not 0/0.
  const std::string path = tmp("straight.png");
  writeDisplayImage(path, kHalfEmptyFull, 3, 1, standardView(), true);
  const test::PngFile png = test::readPng(path);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGB_ALPHA);
  EXPECT_EQ(png.bitDepth, 8);
  ASSERT_EQ(png.samples.size(), 12u);
  const double grey = 255 * srgbEncode(0.18);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(png.samples[size_t(c)], grey, 1) << c;
  EXPECT_EQ(png.samples[3], 128);
  for (int c = 4; c < 8; ++c) EXPECT_EQ(png.samples[size_t(c)], 0) << c;
  for (int c = 8; c < 11; ++c) EXPECT_NEAR(png.samples[size_t(c)], grey, 1) << c;
  EXPECT_EQ(png.samples[11], 255);
}

TEST(DisplayImage, AnOpaqueFrameGivesRgbOverBlack) {
  // Without alpha the premultiplied colour is the pixel over black: sRGB(0.09) = 0.33141 →
  // 84.5, so 84 or 85 (±1 as above).
  const std::string path = tmp("opaque.png");
  writeDisplayImage(path, kHalfEmptyFull, 3, 1, standardView(), false);
  const test::PngFile png = test::readPng(path);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGB);
  ASSERT_EQ(png.samples.size(), 9u);
  EXPECT_NEAR(png.samples[0], 255 * srgbEncode(0.09), 1.5);
  EXPECT_EQ(png.samples[3], 0);
}

TEST(DisplayImage, AViewThatOverflowsIsRefusedAndWritesNothing) {
  // A view whose colour space scales by 1e38 takes a finite grey (16) to infinity, which was
  // written as a black PNG with exit 0. What the view gives is checked as well as what it is
  // given: the image is refused, naming the view and the count (3 channels of the one pixel).
  std::string text = [] {
    std::ifstream f(std::string(GLINT_SOURCE_DIR) + "/ocio/config.ocio");
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  const std::string raw = "{name: Raw, colorspace: Raw}";  // the sRGB display's, the first
  text.replace(text.find(raw), raw.size(), "{name: Raw, colorspace: huge}");
  text +=
      "\n  - !<ColorSpace>\n    name: huge\n    from_scene_reference: !<MatrixTransform> "
      "{matrix: [1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1]}\n";
  DisplaySettings s;
  s.configPath = test::writeTemp("huge-view.ocio", text);
  s.display = "sRGB";
  s.view = "Raw";
  const std::string path = tmp("huge-view.png");
  std::filesystem::remove(path);
  std::string error;
  try {
    writeDisplayImage(path, {16.0f, 16.0f, 16.0f, 1}, 1, 1, s, false);
  } catch (const UsageError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("display \"sRGB\", view \"Raw\" gives 3 colour values that are not "
                       "finite from finite pixels; " +
                       path + " is not written"),
            std::string::npos)
      << error;
  EXPECT_FALSE(std::filesystem::exists(path));
  // The same config's Standard view does not overflow: the check refuses only what is wrong.
  s.view = "Standard";
  writeDisplayImage(path, {0.5f, 0.5f, 0.5f, 1}, 1, 1, s, false);
  EXPECT_TRUE(std::filesystem::exists(path));
}

TEST(DisplayImage, ValuesPastWhiteStayWhiteAndNonFiniteOnesAreNamed) {
  // The default view (ACES 1.0 SDR) took 1e22 to NaN, a black pixel, as it did for 3e38 and
  // infinity; NaN came out black too, all without a word. Values are now given to the view at
  // most at half float's largest, 65504, far past its white: 1e22, 3e38 and infinity are white
  // (255), as 100 is, and NaN is 0. The six non-finite values are counted in one warning.
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> pixels;
  for (const float v : {100.0f, 1e22f, 3e38f, inf, nan}) pixels.insert(pixels.end(), {v, v, v, 1});
  const std::string path = tmp("bright.png");
  testing::internal::CaptureStderr();
  writeDisplayImage(path, pixels, 5, 1, DisplaySettings{}, false);
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("bright.png: 6 colour values are not finite"), std::string::npos) << log;
  const test::PngFile png = test::readPng(path);
  ASSERT_TRUE(png.ok);
  ASSERT_EQ(png.samples.size(), 15u);
  for (size_t i = 0; i < 12; ++i) EXPECT_EQ(png.samples[i], 255) << "sample " << i;
  for (size_t i = 12; i < 15; ++i) EXPECT_EQ(png.samples[i], 0) << "sample " << i;
}

TEST(DisplayImage, ANonFiniteAlphaKeepsItsColourAndIsNamed) {
  // A foreign EXR's NaN alpha made its finite colour black (NaN is not above 0), without a
  // word. NaN and +infinity now read as opaque, -infinity as empty, counted in one warning:
  // grey 0.5 under NaN and +inf alpha shows as grey 0.5 does under alpha 1.
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> pixels = {0.5f, 0.5f, 0.5f, 1,   0.5f, 0.5f, 0.5f, nan,
                                     0.5f, 0.5f, 0.5f, inf, 0.5f, 0.5f, 0.5f, -inf};
  const std::string path = tmp("nan-alpha.png");
  testing::internal::CaptureStderr();
  writeDisplayImage(path, pixels, 4, 1, standardView(), true);
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("nan-alpha.png: 3 alpha values are not finite"), std::string::npos) << log;
  const test::PngFile png = test::readPng(path);
  ASSERT_TRUE(png.ok);
  ASSERT_EQ(png.samples.size(), 16u);
  EXPECT_GT(png.samples[0], 100);  // sRGB(0.5) = 188
  for (size_t p = 1; p < 3; ++p)
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(png.samples[4 * p + c], png.samples[c]) << p << c;
  for (size_t c = 0; c < 4; ++c) EXPECT_EQ(png.samples[12 + c], 0) << c;
}

TEST(DisplayImage, TiffKeepsUnassociatedAlphaAndJpegHasNone) {
  // 16-bit TIFF: alpha 0.5 → 32767.5 → 32768, the colour straight, the file marked
  // unassociated (ExtraSamples 2). Told to keep unassociated alpha, OpenImageIO reads the
  // codes as written; by default it premultiplies what the file says is straight, which
  // halves the half-covered pixel's colour: proof of the mark.
  writeDisplayImage(tmp("straight.tif"), kHalfEmptyFull, 3, 1, standardView(), true);
  OIIO::ImageSpec keepStraight;
  keepStraight.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(tmp("straight.tif"), &keepStraight);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().nchannels, 4);
  EXPECT_EQ(in->spec().get_int_attribute("oiio:UnassociatedAlpha"), 1);
  std::vector<uint16_t> px(12);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT16, px.data()));
  EXPECT_EQ(px[3], 32768);
  const double straight = 65535 * srgbEncode(0.18);  // ±2e-3 as above
  EXPECT_NEAR(px[0], straight, 65535 * 2e-3);
  auto premultiplying = OIIO::ImageInput::open(tmp("straight.tif"));
  ASSERT_TRUE(premultiplying);
  ASSERT_TRUE(premultiplying->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT16, px.data()));
  EXPECT_NEAR(px[0], straight * 32768 / 65535, 65535 * 2e-3);
  writeDisplayImage(tmp("over_black.jpg"), kHalfEmptyFull, 3, 1, standardView(), true);
  auto jpeg = OIIO::ImageInput::open(tmp("over_black.jpg"));
  ASSERT_TRUE(jpeg);
  EXPECT_EQ(jpeg->spec().nchannels, 3);
}

TEST(DisplayImage, PngsCarryTheColourTagOfTheirDisplay) {
  const std::vector<float> grey = {0.18f, 0.18f, 0.18f, 1};
  // sRGB: the sRGB chunk (perceptual intent 0) with the gAMA 1/2.2 libpng writes beside it.
  writeDisplayImage(tmp("srgb.png"), grey, 1, 1, standardView("sRGB"), false);
  const test::PngFile srgb = test::readPng(tmp("srgb.png"));
  ASSERT_TRUE(srgb.ok);
  EXPECT_EQ(srgb.srgbIntent, 0);
  EXPECT_FALSE(srgb.cicp);
  ASSERT_TRUE(srgb.gamma);
  EXPECT_NEAR(*srgb.gamma, 0.45455, 1e-5);
  // Display P3: cICP 12 (SMPTE EG 432-1, P3-D65), 13 (the sRGB curve), 0 (RGB), 1 (full
  // range), cHRM of the P3 primaries and D65, no sRGB chunk (which would claim Rec.709).
  writeDisplayImage(tmp("p3.png"), grey, 1, 1, standardView("Display P3"), false);
  const test::PngFile p3 = test::readPng(tmp("p3.png"));
  ASSERT_TRUE(p3.ok);
  EXPECT_FALSE(p3.srgbIntent);
  EXPECT_EQ(p3.cicp, (std::array<int, 4>{12, 13, 0, 1}));
  ASSERT_TRUE(p3.chrm);
  const std::array<double, 8> p3d65 = {0.3127, 0.3290, 0.680, 0.320, 0.265, 0.690, 0.150, 0.060};
  for (size_t i = 0; i < 8; ++i) EXPECT_NEAR((*p3.chrm)[i], p3d65[i], 1e-5) << i;
  // Rec.1886: cICP 1 (BT.709 primaries), 1 (BT.709 transfer), and gAMA 1/2.4.
  writeDisplayImage(tmp("rec1886.png"), grey, 1, 1, standardView("Rec.1886"), false);
  const test::PngFile rec1886 = test::readPng(tmp("rec1886.png"));
  EXPECT_EQ(rec1886.cicp, (std::array<int, 4>{1, 1, 0, 1}));
  ASSERT_TRUE(rec1886.gamma);
  EXPECT_NEAR(*rec1886.gamma, 1 / 2.4, 1e-5);
  // The Raw view is data, encoded for no display: no tag.
  DisplaySettings raw;
  raw.view = "Raw";
  writeDisplayImage(tmp("raw.png"), grey, 1, 1, raw, false);
  const test::PngFile untagged = test::readPng(tmp("raw.png"));
  EXPECT_FALSE(untagged.srgbIntent);
  EXPECT_FALSE(untagged.cicp);
  EXPECT_FALSE(untagged.gamma);
}

TEST(DisplayImage, StudioConfigDisplayNamesMapToTheirTags) {
  // The ACES studio config's names ("sRGB - Display", "Display P3 - Display", "Rec.1886
  // Rec.709 - Display", "Rec.2100-PQ - Display"); an unknown name has no tag.
  EXPECT_EQ(colourTagForDisplay({"sRGB - Display"}).kind, ColourTag::Kind::Srgb);
  const ColourTag p3 = colourTagForDisplay({"Display P3 - Display"});
  EXPECT_EQ(p3.primaries, 12);
  EXPECT_EQ(p3.transfer, 13);
  EXPECT_EQ(colourTagForDisplay({"Rec.1886 Rec.709 - Display"}).primaries, 1);
  const ColourTag pq = colourTagForDisplay({"Rec.2100-PQ - Display"});
  EXPECT_EQ(pq.primaries, 9);
  EXPECT_EQ(pq.transfer, 16);
  EXPECT_EQ(pq.encodingGamma, 0);  // no power law describes PQ
  EXPECT_EQ(colourTagForDisplay({"Projector", "Cinema"}).kind, ColourTag::Kind::None);
  // The view's colour space decides before the display's name.
  EXPECT_EQ(colourTagForDisplay({"Display P3 - Display", "sRGB"}).primaries, 12);
}

Image withChromaticities(const std::array<float, 8>& c) {
  Image img;
  img.chromaticities = c;
  return img;
}

TEST(InputColorspace, ChromaticitiesNameTheBundledSpaces) {
  // ACES AP0 with the ACES white (SMPTE ST 2065-1), as float in the file.
  const auto ap0 = inputColorspace(
      withChromaticities({0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}),
      "ap0.exr", "");
  EXPECT_EQ(ap0.source, "ACES2065-1");
  EXPECT_FALSE(ap0.toSource);
  const auto rec709 = inputColorspace(
      withChromaticities({0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}), "709.exr",
      "");
  EXPECT_EQ(rec709.source, "lin_rec709");
  // The flag, then glint:colorspace, come before chromaticities.
  EXPECT_EQ(inputColorspace(withChromaticities({}), "x.exr", "ACEScg").source, "ACEScg");
  Image tagged = withChromaticities({0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f});
  tagged.colorspace = "ACEScg";
  EXPECT_EQ(inputColorspace(tagged, "x.exr", "").source, "ACEScg");
  // Neither: the config's scene_linear role.
  EXPECT_EQ(inputColorspace(Image{}, "x.exr", "").source, "");
}

TEST(InputColorspace, OtherChromaticitiesConvertByTheirOwnMatrix) {
  // P3-D65 → Rec.709, both D65 (no adaptation): the published matrix (SMPTE EG 432-1 primaries
  // through XYZ), to its 6 digits.
  const auto p3 = inputColorspace(
      withChromaticities({0.680f, 0.320f, 0.265f, 0.690f, 0.150f, 0.060f, 0.3127f, 0.3290f}),
      "p3.exr", "");
  EXPECT_EQ(p3.source, "lin_rec709");
  ASSERT_TRUE(p3.toSource);
  const std::array<double, 9> p3To709 = {1.224940, -0.224940, 0,         -0.042057, 1.042057,
                                         0,        -0.019638, -0.078636, 1.098274};
  for (size_t i = 0; i < 9; ++i) EXPECT_NEAR((*p3.toSource)[i], p3To709[i], 2e-5) << i;

  // ProPhoto (ROMM) RGB, D50 white: Lindbloom's published ProPhoto → XYZ (D50), Bradford D50 →
  // D65 and XYZ → sRGB matrices, multiplied here. 5e-4: his whites (D50 (0.34567, 0.35850),
  // D65 (0.31271, 0.32902)) differ from ROMM's (0.3457, 0.3585) and Rec.709's (0.3127, 0.3290)
  // in the fourth and fifth digits, which moves entries by up to 3e-4.
  using M = std::array<double, 9>;
  const auto mul = [](const M& a, const M& b) {
    M m{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          m[size_t(3 * r + c)] += a[size_t(3 * r + k)] * b[size_t(3 * k + c)];
    return m;
  };
  const M prophotoToXyz = {0.7976749, 0.1351917, 0.0313534, 0.2880402, 0.7118741,
                           0.0000857, 0.0,       0.0,       0.8252100};
  const M d50ToD65 = {0.9555766, -0.0230393, 0.0631636,  -0.0282895, 1.0099416,
                      0.0210077, 0.0122982,  -0.0204830, 1.3299098};
  const M xyzToSrgb = {3.2404542, -1.5371385, -0.4985314, -0.9692660, 1.8760108,
                       0.0415560, 0.0556434,  -0.2040259, 1.0572252};
  const M expected = mul(xyzToSrgb, mul(d50ToD65, prophotoToXyz));
  const auto prophoto = inputColorspace(
      withChromaticities({0.7347f, 0.2653f, 0.1596f, 0.8404f, 0.0366f, 0.0001f, 0.3457f, 0.3585f}),
      "prophoto.exr", "");
  ASSERT_TRUE(prophoto.toSource);
  for (size_t i = 0; i < 9; ++i) EXPECT_NEAR((*prophoto.toSource)[i], expected[i], 5e-4) << i;
  // White stays white: each row sums to 1.
  for (int r = 0; r < 3; ++r) {
    const M& m = *prophoto.toSource;
    EXPECT_NEAR(m[size_t(3 * r)] + m[size_t(3 * r + 1)] + m[size_t(3 * r + 2)], 1.0, 1e-9) << r;
  }
}

TEST(InputColorspace, ChromaticitiesThatSpanNoSpaceAreRefusedNamingTheFile) {
  // Three primaries on one line (and a white at y = 0) describe no RGB space.
  for (const std::array<float, 8> c :
       {std::array<float, 8>{0.1f, 0.1f, 0.2f, 0.2f, 0.3f, 0.3f, 0.3127f, 0.329f},
        std::array<float, 8>{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3f, 0.0f}}) {
    try {
      inputColorspace(withChromaticities(c), "flat.exr", "");
      FAIL() << "accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("flat.exr"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--input-colorspace"), std::string::npos) << e.what();
    }
  }
}

TEST(DisplayImage, TheBundledConfigsDefaultsAreTheOnesTheHelpStates) {
  // kBundledDefaultDisplay / kBundledDefaultView are what --help says; the config decides.
  const DisplayTransform defaults{DisplaySettings{}};
  EXPECT_EQ(defaults.display(), kBundledDefaultDisplay);
  EXPECT_EQ(defaults.view(), kBundledDefaultView);
}

}  // namespace
}  // namespace glint
