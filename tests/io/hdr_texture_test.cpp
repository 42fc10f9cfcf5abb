// Radiance HDR textures read by Glint (io/hdr_texture.h) against OpenImageIO's HDR reader, which
// read them before: the same header, oiio:ColorSpace and floats, bit for bit, for the repository's
// HDR files, for run-length-encoded files OpenImageIO writes and flat ones written here, over
// every exponent and at every width where the encoding changes; the same refusals for damaged
// files; and the headers left to OpenImageIO.
#include "io/hdr_texture.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/texture_file.h"
#include "io/texture_reader_comparison.h"
#include "test_util.h"

namespace glint {
namespace {

using test::Bytes;
using test::Reading;
using test::writeBytes;

// Random RGB floats spanning many exponents (and some zeros), `seed` fixed.
std::vector<float> randomPixels(int width, int height, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> exponent(-20, 20);
  std::vector<float> pixels(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = random() % 16 == 0 ? 0 : std::exp2(exponent(random)) * float(random() % 256) / 256;
  return pixels;
}

// An HDR file as OpenImageIO writes it: run-length encoded where the width allows.
Bytes writeWithOpenImageIO(int width, int height, uint32_t seed) {
  const std::string path =
      (test::tempDir() / ("oiio-" + std::to_string(width) + "x" + std::to_string(height) + ".hdr"))
          .string();
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out);
  if (!out) return {};
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  EXPECT_TRUE(out->open(path, spec)) << out->geterror();
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, randomPixels(width, height, seed).data()));
  out->close();
  const std::string file = test::readFile(path);
  return Bytes(file.begin(), file.end());
}

// A flat (not run-length encoded) file with `header` before its size line, of the given RGBE
// pixels.
Bytes flatFile(int width, int height, const std::vector<unsigned char>& rgbe,
               const std::string& header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n") {
  const std::string head =
      header + "-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
  Bytes file(head.begin(), head.end());
  file.insert(file.end(), rgbe.begin(), rgbe.end());
  return file;
}

void compareBytes(const std::string& name, const Bytes& bytes) {
  test::compareBytes(kHdrReader, name, bytes);
}

// Written to a file and compared from it and from memory.
void compareEverywhere(const std::string& name, const Bytes& bytes) {
  const std::string path = (test::tempDir() / (name + ".hdr")).string();
  writeBytes(path, bytes);
  test::compareFile(kHdrReader, path);
  compareBytes("embedded " + name + ".hdr", bytes);
}

TEST(HdrTexture, EveryHdrOfTheRepositoryGivesOpenImageIOsFloats) {
  const std::vector<std::string> files = test::filesUnder(GLINT_SOURCE_DIR, {".hdr", ".rgbe"});
  ASSERT_GE(files.size(), 1u);  // scenes/sky.hdr
  for (const std::string& path : files) {
    const Reading r = test::readWith(kHdrReader, path);
    ASSERT_FALSE(r.declined) << path;
    test::expectSameReading(kHdrReader.library, r, test::readWithOpenImageIO(path), path);
  }
}

TEST(HdrTexture, RunLengthAndFlatScanlinesGiveOpenImageIOsFloats) {
  // Widths below 8 and above 0x7fff are flat; between them OpenImageIO writes runs and literals.
  uint32_t seed = 1;
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{8, 2},
                                      std::pair{9, 5}, std::pair{300, 7}, std::pair{0x8000, 1}})
    compareEverywhere("oiio " + std::to_string(width) + "x" + std::to_string(height),
                      writeWithOpenImageIO(width, height, seed++));
  // Flat files: every exponent (0 is black whatever the mantissas) with every mantissa byte, in
  // scanlines wide enough that each one's start is checked for the run-length marker.
  std::vector<unsigned char> rgbe;
  for (int e = 0; e < 256; ++e)
    for (int m = 0; m < 256; m += 5)
      rgbe.insert(rgbe.end(), {uint8_t(m), uint8_t(255 - m), uint8_t(m / 2), uint8_t(e)});
  const int width = 52, height = int(rgbe.size() / 4 / 52);
  rgbe.resize(size_t(width) * size_t(height) * 4);
  compareEverywhere("flat every exponent", flatFile(width, height, rgbe));
  // A byte times 2^(e − 136) as OpenImageIO's table has it (eight significant digits): exact
  // for e = 128 + k, k = 0..8 (2^−8 to 1), one ulp below 2^−96 for e = 40.
  const Reading r = test::readBytesWith(kHdrReader, "flat.hdr", flatFile(width, height, rgbe));
  ASSERT_TRUE(r.ok) << r.error;
  for (size_t p = 0; p < r.texels.size() / 3; ++p) {
    const int e = rgbe[4 * p + 3], m = rgbe[4 * p];
    if (e >= 128 && e <= 136) {
      EXPECT_EQ(r.texels[3 * p], std::ldexp(float(m), e - 136)) << p;
    }
    if (e == 40) {
      EXPECT_EQ(r.texels[3 * p], float(m) * std::nextafter(std::ldexp(1.0f, -96), 0.0f)) << p;
    }
  }
}

TEST(HdrTexture, HeaderLinesAreReadAsOpenImageIOReadsThem) {
  const std::vector<unsigned char> grey(4 * 9 * 2, 0x80);
  // Other header lines (EXPOSURE, comments, a line of 300 bytes that OpenImageIO reads in
  // pieces of 128), "#?RGBE", FORMAT after them: read the same.
  for (const std::string& header :
       {std::string("#?RGBE\nFORMAT=32-bit_rle_rgbe\n\n"),
        std::string("#?RADIANCE\n# made by hand\nEXPOSURE=2.5\nFORMAT=32-bit_rle_rgbe\n\n"),
        "#?RADIANCE\n#" + std::string(300, 'x') + "\nFORMAT=32-bit_rle_rgbe\n\n"})
    compareEverywhere("header " + std::to_string(header.size()), flatFile(9, 2, grey, header));
  // Refused by both: no FORMAT, a FORMAT past 100 lines or after a blank line, another format.
  std::string many = "#?RADIANCE\n";
  for (int i = 0; i < 101; ++i) many += "# line\n";
  for (const std::string& header :
       {std::string("#?RADIANCE\n\n"), many + "FORMAT=32-bit_rle_rgbe\n\n",
        std::string("#?RADIANCE\nSOFTWARE=test\n\nFORMAT=32-bit_rle_rgbe\n\n"),
        std::string("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n")}) {
    const Reading r = test::readBytesWith(kHdrReader, "bad.hdr", flatFile(9, 2, grey, header));
    EXPECT_FALSE(r.ok) << header;
    compareBytes("bad header " + std::to_string(header.size()) + ".hdr",
                 flatFile(9, 2, grey, header));
  }
}

TEST(HdrTexture, EveryOrientationIsTurnedUpright) {
  // Radiance's eight resolution strings: scanlines along Y (rows) or X (columns), each axis
  // either way. OpenImageIO reads the pixels in the file's order and leaves the turn to its
  // caller (as metadata Glint did not read): a "+Y" sky lit the scene upside down. Each file
  // here holds the same 9 x 2 image (distinct pixels) and must read as the "-Y 2 +X 9" one.
  const int width = 9, height = 2;
  std::vector<unsigned char> upright;
  for (int p = 0; p < width * height; ++p)
    test::append(upright, {static_cast<unsigned char>(10 + p), static_cast<unsigned char>(100 + p),
                           static_cast<unsigned char>(200 - p), 128});
  const test::Reading reference =
      test::readBytesWith(kHdrReader, "upright.hdr", flatFile(width, height, upright));
  ASSERT_TRUE(reference.ok) << reference.error;
  for (const bool yFirst : {true, false})
    for (const char ySign : {'-', '+'})
      for (const char xSign : {'+', '-'}) {
        const int scanlines = yFirst ? height : width, length = yFirst ? width : height;
        const std::string y = std::string(1, ySign) + "Y " + std::to_string(height);
        const std::string x = std::string(1, xSign) + "X " + std::to_string(width);
        const std::string size = (yFirst ? y + " " + x : x + " " + y) + "\n";
        const std::string head = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + size;
        Bytes file(head.begin(), head.end());
        for (int s = 0; s < scanlines; ++s)
          for (int i = 0; i < length; ++i) {
            const int alongY = yFirst ? s : i, alongX = yFirst ? i : s;
            const int row = ySign == '-' ? alongY : height - 1 - alongY;
            const int column = xSign == '+' ? alongX : width - 1 - alongX;
            const auto* pixel = &upright[size_t(4 * (row * width + column))];
            file.insert(file.end(), pixel, pixel + 4);
          }
        const test::Reading turned = test::readBytesWith(kHdrReader, "turned.hdr", file);
        ASSERT_TRUE(turned.ok) << size << turned.error;
        EXPECT_EQ(turned.info.width, width) << size;
        EXPECT_EQ(turned.info.height, height) << size;
        EXPECT_EQ(turned.texels, reference.texels) << size;
      }
  // Two written out by hand, apart from the formula above: "+Y" holds the bottom row first;
  // "+X 9 -Y 2" holds columns from the left, each from the top.
  const std::string head = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  Bytes bottomFirst(head.begin(), head.end());
  test::append(bottomFirst, {'+', 'Y', ' ', '2', ' ', '+', 'X', ' ', '9', '\n'});
  bottomFirst.insert(bottomFirst.end(), upright.begin() + 36, upright.end());    // row 1
  bottomFirst.insert(bottomFirst.end(), upright.begin(), upright.begin() + 36);  // row 0
  Bytes columns(head.begin(), head.end());
  test::append(columns, {'+', 'X', ' ', '9', ' ', '-', 'Y', ' ', '2', '\n'});
  for (size_t column = 0; column < 9; ++column)
    for (size_t row = 0; row < 2; ++row) {
      const auto* pixel = &upright[4 * (row * 9 + column)];
      columns.insert(columns.end(), pixel, pixel + 4);
    }
  for (const auto& [what, file] : {std::pair{"+Y 2 +X 9", bottomFirst}, {"+X 9 -Y 2", columns}})
    EXPECT_EQ(test::readBytesWith(kHdrReader, "by-hand.hdr", file).texels, reference.texels)
        << what;
  // A file of another orientation too short for its pixels is refused from its header.
  const std::string cut = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 8000 +X 8000\n";
  const test::Reading tooShort =
      test::readBytesWith(kHdrReader, "cut.hdr", Bytes(cut.begin(), cut.end()));
  EXPECT_FALSE(tooShort.declined || tooShort.ok);
  EXPECT_NE(tooShort.error.find("8000 x 8000 pixels cannot fit in the 0 bytes after the header"),
            std::string::npos)
      << tooShort.error;
}

TEST(HdrTexture, GammaOtherSizeLinesAndOtherFormatsAreLeftToOpenImageIO) {
  // GAMMA names a colour space in OpenImageIO; size lines that are not Radiance's strict form
  // (doubled spaces, one axis twice); a first line without "#?" may be another format; names
  // that are not .hdr or .rgbe.
  const std::vector<unsigned char> grey(4 * 9 * 2, 0x80);
  EXPECT_TRUE(
      test::readBytesWith(kHdrReader, "g.hdr",
                          flatFile(9, 2, grey, "#?RADIANCE\nGAMMA=2.2\nFORMAT=32-bit_rle_rgbe\n\n"))
          .declined);
  const std::string body = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  for (const std::string size : {"-Y  2 +X 9\n", "+Y 2 -Y 9\n", "-Y 2 +X 9 \n", "Y 2 X 9\n"}) {
    Bytes file(body.begin(), body.end());
    file.insert(file.end(), size.begin(), size.end());
    file.insert(file.end(), grey.begin(), grey.end());
    EXPECT_TRUE(test::readBytesWith(kHdrReader, "o.hdr", file).declined) << size;
  }
  const Bytes plain = flatFile(9, 2, grey);
  EXPECT_TRUE(test::readBytesWith(kHdrReader, "t.exr", plain).declined);
  EXPECT_FALSE(test::readBytesWith(kHdrReader, "t.HDR", plain).declined);
  EXPECT_FALSE(test::readBytesWith(kHdrReader, "t.rgbe", plain).declined);
  EXPECT_TRUE(
      test::readBytesWith(kHdrReader, "t.hdr", flatFile(9, 2, grey, "RADIANCE\n\n")).declined);
  // The GAMMA file still opens, through OpenImageIO.
  const std::string path = (test::tempDir() / "gamma.hdr").string();
  writeBytes(path, flatFile(9, 2, grey, "#?RADIANCE\nGAMMA=2.2\nFORMAT=32-bit_rle_rgbe\n\n"));
  EXPECT_EQ(openImageTexture(path)->path(), path);
}

TEST(HdrTexture, TruncatedAndCorruptedFilesAreRefusedAsOpenImageIORefusesThem) {
  // Every length short of the whole file, and every byte inverted, of a run-length-encoded file
  // and a flat one: both readers refuse it, or both read the same floats (under AddressSanitizer
  // compared at every eighth file: test::compareDamaged). A header damaged into one Glint leaves
  // to OpenImageIO (another orientation) is OpenImageIO's to read.
  size_t call = 0;
  const std::vector<unsigned char> flat = {1, 2, 3, 130, 200, 100, 50, 129, 0, 0, 0, 0,
                                           9, 8, 7, 128, 4,   5,   6,  127, 1, 1, 1, 140};
  for (const auto& [tag, good] : {std::pair{"rle", writeWithOpenImageIO(12, 3, 7)},
                                  std::pair{"flat", flatFile(3, 2, flat)}}) {
    for (size_t n = 2; n < good.size(); ++n)
      test::compareDamaged(kHdrReader,
                           std::string("cut at ") + std::to_string(n) + " " + tag + ".hdr",
                           Bytes(good.begin(), good.begin() + long(n)), call++);
    for (size_t i = 2; i < good.size(); ++i) {
      Bytes bad = good;
      bad[i] ^= 0xff;
      test::compareDamaged(kHdrReader, "byte " + std::to_string(i) + " inverted " + tag + ".hdr",
                           bad, call++);
    }
  }
}

TEST(HdrTexture, AHostileFileIsRefusedNamingTheFileAndWhatWasWrong) {
  // A run longer than its scanline (padded to the 12 bytes an encoded scanline of 8 takes at
  // least), and a header declaring 999999999 x 999999999 over 4 bytes, refused before any
  // texel's memory is allocated: both through the texture reader, naming the file.
  Bytes file = flatFile(8, 1, {});
  test::append(file, {2, 2, 0, 8, 200, 1, 0, 0, 0, 0, 0, 0});  // a run of 72 in a row of 8
  const std::string run = (test::tempDir() / "run.hdr").string();
  writeBytes(run, file);
  test::expectRefusedNaming(run, "invalid HDR data: bad scanline 0 data");
  const std::string huge = (test::tempDir() / "huge.hdr").string();
  writeBytes(huge, flatFile(999999999, 999999999, {1, 2, 3, 4}));
  test::expectRefusedNaming(
      huge, "999999999 x 999999999 pixels cannot fit in the 4 bytes after the header");
  // A size of 20 digits went to OpenImageIO, which clamped it to 2^31 - 1 and ran out of memory
  // (exit 1, as if the machine had failed).
  const std::string head = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 99999999999999999999 +X 8\n";
  const std::string longSize = (test::tempDir() / "long-size.hdr").string();
  writeBytes(longSize, Bytes(head.begin(), head.end()));
  test::expectRefusedNaming(longSize, "invalid HDR data: its size line gives a size of 10 digits");
}

}  // namespace
}  // namespace glint
