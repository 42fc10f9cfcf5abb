// Image files read as textures (io/texture_file.h): what OpenImageIO reads is what the MIP
// pyramid holds, whatever the file's layout.
#include "io/texture_file.h"

#include <gtest/gtest.h>

#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imageio.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "film/oiio_module.h"
#include "io/texture_bands.h"
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

// Why openImageTexture refused `path` ("(accepted)" if it did not).
std::string textureRefusal(const std::string& path) {
  try {
    openImageTexture(path);
  } catch (const GlintError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(TextureFile, AnExrsFirstChannelsMustBeAColourOrAVector) {
  // A frame's AOV layers (Z, then foo.R ...) had Z read as red, and a chroma image (Y, RY, BY)
  // rendered grey. Three or more channels must begin with R, G, B or X, Y, Z of one layer.
  const auto refusal = [](const std::string& name, std::vector<std::string> channels) {
    const std::string path = (test::tempDir() / (name + ".exr")).string();
    OIIO::ImageSpec spec(2, 2, int(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = std::move(channels);
    const std::vector<float> texels(size_t(4 * spec.nchannels), 0.5f);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close());
    return textureRefusal(path);
  };
  EXPECT_EQ(refusal("rgba", {"R", "G", "B", "A"}), "(accepted)");
  EXPECT_EQ(refusal("layer", {"diffuse.R", "diffuse.G", "diffuse.B"}), "(accepted)");
  EXPECT_EQ(refusal("normal", {"N.X", "N.Y", "N.Z"}), "(accepted)");
  EXPECT_EQ(refusal("spelled", {"Red", "Green", "Blue"}), "(accepted)");
  EXPECT_EQ(refusal("lower", {"x", "y", "z"}), "(accepted)");
  const std::string aov = refusal("aov", {"Z", "foo.R", "foo.G", "foo.B"});
  EXPECT_NE(aov.find("aov.exr: its channels are Z, foo.R, foo.G, foo.B; Glint reads a "
                     "texture's first three channels as R, G, B (or X, Y, Z)"),
            std::string::npos)
      << aov;
  EXPECT_NE(refusal("chroma", {"Y", "RY", "BY"}).find("its channels are Y, BY, RY;"),
            std::string::npos);
  EXPECT_NE(refusal("mixed", {"a.R", "b.G", "a.B"}).find("its channels are"), std::string::npos);
}

TEST(TextureFile, ADeepImageIsRefusedByName) {
  // OpenImageIO opened it, then failed its first read: "called read_native_scanlines without
  // an open file".
  const std::string path = (test::tempDir() / "deep.exr").string();
  OIIO::ImageSpec spec(2, 2, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "A"};
  spec.deep = true;
  OIIO::DeepData deep(spec);
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) && out->write_deep_image(deep) && out->close());
  EXPECT_EQ(textureRefusal(path),
            "cannot read texture " + path + ": it holds deep data, which Glint does not read");
}

TEST(TextureFile, OnlyTheFormatsGlintListsReachOpenImageIOsReaders) {
  // OpenImageIO's IFF reader corrupted the heap on a 268-byte file, its DPX reader asserted, its
  // SGI reader took 4.3 GB for 512 bytes: a texture reaches only the readers of
  // io/texture_formats.h, chosen by its extension and never by its bytes.
  const int width = 4, height = 2;
  std::vector<float> texels(size_t(width) * height * 3);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i % 7) / 7;
  const auto write = [&](const std::string& name) {
    const std::string path = (test::tempDir() / name).string();
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)) &&
                out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close());
    return path;
  };
  const std::string iff = write("checker.iff");
  EXPECT_EQ(textureRefusal(iff),
            "cannot read texture " + iff +
                ": \".iff\" is not an image format Glint reads textures from; Glint reads PNG, "
                "JPEG, Radiance HDR (.hdr), OpenEXR (.exr), TIFF (.tif, .tiff, .tx), Photoshop "
                "(.psd), Targa (.tga), BMP (.bmp) and PNM (.ppm, .pgm, .pfm) files, by their "
                "extension (oiiotool converts the others: oiiotool IN -o OUT.exr)");
  // The same bytes named as a TIFF meet the TIFF reader alone, which refuses them (OpenImageIO's
  // ImageInput::open went on to try every reader on them).
  const std::string disguised = (test::tempDir() / "checker_iff.tif").string();
  std::filesystem::copy_file(iff, disguised, std::filesystem::copy_options::overwrite_existing);
  const std::string refusal = textureRefusal(disguised);
  EXPECT_EQ(refusal.rfind("cannot read texture " + disguised + ": ", 0), 0u) << refusal;
  EXPECT_NE(refusal.find("TIFF"), std::string::npos) << refusal;
  // The listed formats OpenImageIO reads give the file's texels (8-bit codes, exact to 1e-6).
  for (const char* name : {"checker.tga", "checker.bmp", "checker.ppm"}) {
    SCOPED_TRACE(name);
    const auto t = openImageTexture(write(name));
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = 3 * (size_t(y) * width + size_t(x));
        const Rgb texel = texelAt(*t, width, height, x, y);
        EXPECT_NEAR(texel.r, std::round(texels[i] * 255) / 255, 1e-6);
        EXPECT_NEAR(texel.b, std::round(texels[i + 2] * 255) / 255, 1e-6);
      }
  }
}

// A 2 × 2 RGB Photoshop file of 8-bit raw texels (red 10, 20, 30, 40; green 50 ...; blue 90
// ...), its colour mode data section claiming `colourModeBytes` (holding none).
std::string photoshopFile(uint32_t colourModeBytes) {
  std::string f = "8BPS";
  const auto be = [&](uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) f += char((v >> (8 * i)) & 0xff);
  };
  be(1, 2);                   // version 1: PSD
  f += std::string(6, '\0');  // reserved
  be(3, 2);                   // channels
  be(2, 4), be(2, 4);         // height, width
  be(8, 2), be(3, 2);         // depth, colour mode RGB
  be(colourModeBytes, 4);     // colour mode data
  be(0, 4), be(0, 4);         // image resources, layer and mask information
  be(0, 2);                   // image data, raw: each channel's plane in turn
  for (int v = 10; v <= 120; v += 10) f += char(v);
  return f;
}

TEST(TextureFile, APhotoshopFileWhoseSectionsRunPastItsEndIsRefusedBeforeItIsRead) {
  // OpenImageIO's PSD reader allocates what a section's length claims: 66 bytes claiming
  // 4 GiB of colour mode data took 4.3 GB and 13 s before they failed.
  const std::string good = (test::tempDir() / "good.psd").string();
  std::ofstream(good, std::ios::binary) << photoshopFile(0);
  const auto t = openImageTexture(good);
  const Rgb texel = texelAt(*t, 2, 2, 1, 0);  // the second texel of each plane
  EXPECT_NEAR(texel.r, 20 / 255.0f, 1e-6);
  EXPECT_NEAR(texel.g, 60 / 255.0f, 1e-6);
  EXPECT_NEAR(texel.b, 100 / 255.0f, 1e-6);
  const std::string bad = (test::tempDir() / "bad.psd").string();
  std::ofstream(bad, std::ios::binary) << photoshopFile(0xffffffff);
  EXPECT_EQ(textureRefusal(bad), "cannot read texture " + bad +
                                     ": its colour mode data claims 4294967295 bytes, but 22 "
                                     "remain (a cut or damaged Photoshop file)");
}

TEST(TextureFile, NegativeValuesCountAsZeroAsAColourButStayAsData) {
  // A float texture of (-1, 0.5, -0.25) rendered a negative red into the frame as a diffuse
  // colour, without a word. As data (a normal map's) negative values are meaningful.
  const std::string path = (test::tempDir() / "negative.exr").string();
  OIIO::ImageSpec spec(2, 2, 3, OIIO::TypeDesc::FLOAT);
  const std::vector<float> texels = {-1, 0.5f, -0.25f, -1, 0.5f, -0.25f,
                                     -1, 0.5f, -0.25f, -1, 0.5f, -0.25f};
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close());
  testing::internal::CaptureStderr();
  const auto t = openImageTexture(path);
  const ImageFootprint at{{0.5f, 0.5f}, {0, 0}, {0, 0}};
  const Rgb data = t->data(at);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");  // a normal map's values: no warning
  testing::internal::CaptureStderr();
  const Rgb colour = t->color(at);  // a float file: linear, no conversion
  t->color(at);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "glint: warning: texture " + path +
                ": 8 colour values are negative; as a colour the image is read with them as 0\n");
  EXPECT_EQ(data.r, -1.0f);
  EXPECT_EQ(data.b, -0.25f);
  EXPECT_EQ(colour.r, 0.0f);
  EXPECT_EQ(colour.g, 0.5f);
  EXPECT_EQ(colour.b, 0.0f);
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

// OpenImageIO's module reads a texture's band in the file's own type and converts it to float
// itself (film/oiio_plugin.cpp): in bands of 4 rows, for the first 4 of 5 channels (the file's
// every channel is read and 4 kept), each type must give the very floats OpenImageIO's own
// conversion gives for the whole image.
TEST(TextureFile, BandsReadInTheFilesTypeGiveOpenImageIOsFloats) {
  const int width = 23, height = 17, fileChannels = 5, kept = 4, bandRows = 4;
  std::vector<float> values(size_t(width) * height * fileChannels);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-0.25f, 1.25f);  // clamped by the integer types
  for (float& v : values) v = value(rng);
  const auto& functions = oiio_module::textureFunctions("bands.tif");
  for (const auto& [type, extension] :
       {std::pair{OIIO::TypeDesc::UINT8, "tif"}, std::pair{OIIO::TypeDesc::UINT16, "tif"},
        std::pair{OIIO::TypeDesc::FLOAT, "tif"}, std::pair{OIIO::TypeDesc::HALF, "exr"}}) {
    const std::string path =
        (test::tempDir() / ("bands_" + std::string(OIIO::TypeDesc(type).c_str()) + "." + extension))
            .string();
    SCOPED_TRACE(path);
    const OIIO::ImageSpec spec(width, height, fileChannels, type);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close());
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    ASSERT_EQ(in->spec().format, type);  // the file holds the type under test
    std::vector<float> expected(size_t(width) * height * kept);
    ASSERT_TRUE(in->read_image(0, 0, 0, kept, OIIO::TypeDesc::FLOAT, expected.data()));

    GlintOiioTextureInfo info{};
    char error[512] = "";
    void* handle =
        functions.open(path.c_str(), extension == std::string("exr") ? "openexr" : "tiff", &info,
                       error, sizeof error);
    ASSERT_NE(handle, nullptr) << error;
    const std::unique_ptr<void, GlintOiioTextureClose> opened(handle, functions.close);
    ASSERT_EQ(info.channels, fileChannels);
    std::vector<float> read;
    std::string readError;
    ASSERT_TRUE(
        test::readInBands(functions, handle, width, height, kept, bandRows, read, readError))
        << readError;
    for (size_t i = 0; i < read.size(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(read[i]), std::bit_cast<uint32_t>(expected[i])) << i;
  }
}

}  // namespace
}  // namespace glint
