// Display and difference images (film/image_file.h): PNG through libpng gives the bytes
// OpenImageIO's PNG writer gives for the same pixels (what Glint wrote before it left
// OpenImageIO out of the start path), and the other formats go through OpenImageIO's module.
#include "film/image_file.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <random>

#include "core/error.h"
#include "test_util.h"

namespace glint {
namespace {

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

std::string writtenByOpenImageIO(const std::string& name, int w, int h,
                                 const std::vector<uint8_t>& rgb) {
  const std::string path = tmp(name);
  auto out = OIIO::ImageOutput::create(path);
  const OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
  EXPECT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) &&
              out->close());
  return test::readFile(path);
}

TEST(ImageFile, PngBytesEqualOpenImageIOsForTheSamePixels) {
  // A smooth ramp (long runs that compress), fixed-seed noise (that does not) and a frame
  // larger than libpng's 8 kB IDAT chunks: the zlib level and strategy, the filters and the
  // chunk layout must all agree for the bytes to.
  struct Case {
    const char* name;
    int w, h;
    bool noise;
  };
  for (const Case c :
       {Case{"ramp", 37, 21, false}, Case{"noise", 64, 48, true}, Case{"large", 320, 200, false}}) {
    std::vector<uint16_t> codes(size_t(c.w) * size_t(c.h) * 3);
    std::mt19937 rng(7);
    for (size_t i = 0; i < codes.size(); ++i)
      codes[i] = uint16_t(c.noise ? rng() % 256 : (i * 7 / 3 + i / (size_t(c.w) * 3)) % 256);
    const std::string mine = tmp(std::string(c.name) + ".png");
    writeRgbImage(mine, c.w, c.h, 8, codes);
    const std::vector<uint8_t> bytes(codes.begin(), codes.end());
    const std::string theirs =
        writtenByOpenImageIO(std::string(c.name) + "-oiio.png", c.w, c.h, bytes);
    ASSERT_GT(theirs.size(), 100u) << c.name;
    EXPECT_EQ(test::readFile(mine), theirs) << c.name;
  }
}

TEST(ImageFile, SixteenBitTiffThroughTheModuleKeepsEveryCode) {
  const int w = 5, h = 3;
  std::vector<uint16_t> codes(size_t(w) * size_t(h) * 3);
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(i * 4369);  // 0 … 65535 - 4369
  writeRgbImage(tmp("codes.tif"), w, h, 16, codes);
  auto in = OIIO::ImageInput::open(tmp("codes.tif"));
  ASSERT_TRUE(in);
  std::vector<uint16_t> back(codes.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT16, back.data()));
  EXPECT_EQ(back, codes);
}

TEST(ImageFile, LibpngsErrorsAreGlintErrorsNamingTheFileAndLeaveNothing) {
  // An image of no pixels: libpng refuses the header (png_error, its longjmp path).
  const std::string path = tmp("empty.png");
  try {
    writeRgbImage(path, 0, 0, 8, {});
    FAIL() << "wrote " << path;
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("IHDR"), std::string::npos) << e.what();  // libpng's words
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace glint
