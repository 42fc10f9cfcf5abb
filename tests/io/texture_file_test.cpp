// Image files read as textures (io/texture_file.h): what OpenImageIO reads is what the MIP
// pyramid holds, whatever the file's layout.
#include "io/texture_file.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <memory>
#include <vector>

#include "test_util.h"

namespace glint {
namespace {

// A width × height float image of `channels` whose texel (x, y), channel c is x + 100·y + c/4
// (exact in float), tiled or in scanlines.
void writeImage(const std::string& path, int width, int height, int channels, int tile) {
  std::vector<float> texels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) texels.push_back(float(x + 100 * y) + 0.25f * float(c));
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  if (tile > 0) spec.tile_width = spec.tile_height = tile;
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close());
}

// The texel (x, y) read with no footprint at its centre, as data (no colour conversion).
Rgb texelAt(const ImageTexture& t, int width, int height, int x, int y) {
  return t.data(
      {{(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)}, {0, 0}, {0, 0}});
}

TEST(TextureFile, TiledAndScanlineFilesGiveTheSameTexels) {
  // OpenImageIO 2.4 divided by zero reading a tiled file by scanlines (SIGFPE): tiles are read
  // as tiles. A 37 × 21 image in 8 × 8 tiles (partial tiles at the right and bottom edges)
  // must give every texel as the file holds it, as the same image in scanlines does.
  const int width = 37, height = 21;
  const std::string tiled = (test::tempDir() / "tiled_texture.exr").string();
  const std::string lines = (test::tempDir() / "scanline_texture.exr").string();
  writeImage(tiled, width, height, 3, 8);
  writeImage(lines, width, height, 3, 0);
  const auto a = openImageTexture(tiled), b = openImageTexture(lines);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb ta = texelAt(*a, width, height, x, y), tb = texelAt(*b, width, height, x, y);
      // A texel centre with no footprint is the texel itself, up to float rounding of the
      // bilinear weights at coordinates ≤ 37 (1e-3).
      EXPECT_NEAR(ta.r, float(x + 100 * y), 1e-3) << x << " " << y;
      EXPECT_NEAR(ta.b, float(x + 100 * y) + 0.5f, 1e-3) << x << " " << y;
      EXPECT_EQ(ta.r, tb.r);
      EXPECT_EQ(ta.g, tb.g);
      EXPECT_EQ(ta.b, tb.b);
    }
  // The environment's unfiltered texels: exactly the file's.
  const LatLongImage image = readTexels(*a, 12);
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  EXPECT_EQ(image.texels[size_t(5 * width + 7)].r, 507.0f);
  EXPECT_EQ(image.texels[size_t(5 * width + 7)].g, 507.25f);
}

TEST(TextureFile, AGreyAlphaImageGivesItsGreyToColourAndItsAlphaToCoverage) {
  const std::string path = (test::tempDir() / "grey_alpha.exr").string();
  writeImage(path, 4, 4, 2, 0);
  const auto t = openImageTexture(path);
  const ImageFootprint at{{2.5f / 4, 1.5f / 4}, {0, 0}, {0, 0}};  // texel (2, 1): 102
  const Rgb c = t->data(at);
  EXPECT_NEAR(c.r, 102, 1e-4);
  EXPECT_NEAR(c.g, 102, 1e-4);
  EXPECT_NEAR(c.b, 102, 1e-4);
  EXPECT_NEAR(t->coverage(at, false), 102.25, 1e-4);  // its second channel
}

}  // namespace
}  // namespace glint
