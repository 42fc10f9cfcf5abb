// PNG textures read by libpng (io/png_texture.h) against OpenImageIO's PNG reader, which read
// them before: the same header, oiio:ColorSpace and floats, bit for bit, for every PNG in the
// repository and Assimp's test models and for every PNG variant (bit depths, colour types,
// palettes with and without tRNS, Adam7, colour chunks); the same refusals for damaged files.
#include "io/png_texture.h"

#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
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

Reading readWithLibpng(const std::string& path) { return test::readWith(kPngReader, path); }

Reading readBytesWithLibpng(const std::string& name, const Bytes& bytes) {
  return test::readBytesWith(kPngReader, name, bytes);
}

void compareFile(const std::string& path) { test::compareFile(kPngReader, path); }

void compareBytes(const std::string& name, const Bytes& bytes) {
  test::compareBytes(kPngReader, name, bytes);
}

// A PNG to write: its header, chunks and (random) samples.
struct Variant {
  int width = 13, height = 7;  // odd sizes: Adam7's passes end part-way
  int bitDepth = 8, colorType = PNG_COLOR_TYPE_RGB;
  bool interlaced = false;
  bool trns = false;  // tRNS: a palette's alphas, or a grey or RGB colour made transparent
  double gamma = 0;   // gAMA's encoding exponent (0: none)
  bool srgb = false;  // sRGB chunk
  bool iccp = false;  // iCCP chunk (an RGB or grey profile of no tags)
  std::vector<std::pair<std::string, std::string>> texts;  // tEXt chunks
  bool exif = false;                                       // eXIf chunk
  uint32_t seed = 1;
  // All codes of the bit depth in order, each once, instead of random samples.
  bool everyCode = false;
};

void storeWriteError(png_structp png, png_const_charp message) {
  ADD_FAILURE() << "libpng cannot write the test PNG: " << message;
  png_longjmp(png, 1);
}

void appendBytes(png_structp png, png_bytep data, size_t length) {
  auto* out = static_cast<Bytes*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}

// A minimal ICC profile: header only, no tags; libpng checks its size, signature and colour
// space and keeps it, OpenImageIO decodes its header into ICCProfile: attributes.
std::string iccProfile(bool grey) {
  std::string p(132, '\0');
  p[3] = char(132);
  std::memcpy(&p[12], "mntr", 4);
  std::memcpy(&p[16], grey ? "GRAY" : "RGB ", 4);
  std::memcpy(&p[20], "XYZ ", 4);
  std::memcpy(&p[36], "acsp", 4);
  // D50 illuminant, s15Fixed16: 0.9642, 1.0, 0.8249.
  const unsigned char d50[12] = {0, 0, 0xf6, 0xd6, 0, 1, 0, 0, 0, 0, 0xd3, 0x2d};
  std::memcpy(&p[68], d50, 12);
  return p;
}

Bytes writePng(const Variant& v) {
  Bytes out;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, storeWriteError, nullptr);
  png_infop info = png_create_info_struct(png);
  const int channels = v.colorType == PNG_COLOR_TYPE_RGB          ? 3
                       : v.colorType == PNG_COLOR_TYPE_RGB_ALPHA  ? 4
                       : v.colorType == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                                                                  : 1;
  const size_t rowBytes = (size_t(v.width) * size_t(channels) * size_t(v.bitDepth) + 7) / 8;
  Bytes samples(rowBytes * size_t(v.height));
  std::mt19937 random(v.seed);
  for (size_t i = 0; i < samples.size(); ++i)
    samples[i] = static_cast<unsigned char>(
        v.everyCode ? (v.bitDepth == 16 ? (i % 2 ? i / 2 % 256 : i / 2 / 256 % 256) : i % 256)
                    : random());
  std::vector<png_bytep> rows;
  for (int y = 0; y < v.height; ++y) rows.push_back(&samples[size_t(y) * rowBytes]);
  const std::string profile = iccProfile(channels < 3);
  std::vector<png_text> texts;
  for (const auto& [key, text] : v.texts) {
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(key.c_str());
    t.text = const_cast<char*>(text.c_str());
    texts.push_back(t);
  }
  if (setjmp(png_jmpbuf(png)) == 0) {
    png_set_write_fn(png, &out, appendBytes, nullptr);
    png_set_IHDR(png, info, png_uint_32(v.width), png_uint_32(v.height), v.bitDepth, v.colorType,
                 v.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (v.colorType == PNG_COLOR_TYPE_PALETTE) {
      // Every index the bit depth can hold has a colour.
      std::vector<png_color> palette(size_t(1) << v.bitDepth);
      for (size_t i = 0; i < palette.size(); ++i)
        palette[i] = {png_byte(random()), png_byte(random()), png_byte(random())};
      png_set_PLTE(png, info, palette.data(), int(palette.size()));
      if (v.trns) {
        std::vector<png_byte> alphas(palette.size() / 2 + 1);
        for (png_byte& a : alphas) a = png_byte(random());
        png_set_tRNS(png, info, alphas.data(), int(alphas.size()), nullptr);
      }
    } else if (v.trns) {
      // The colour of the first texel, so that some texels are transparent.
      png_color_16 colour{};
      const int bytes = v.bitDepth == 16 ? 2 : 1;
      auto sample = [&](int c) -> png_uint_16 {
        if (v.bitDepth < 8) return png_uint_16(samples[0] >> (8 - v.bitDepth));
        return bytes == 2 ? png_uint_16(samples[size_t(2 * c)] << 8 | samples[size_t(2 * c + 1)])
                          : samples[size_t(c)];
      };
      if (channels == 1) {
        colour.gray = sample(0);
      } else {
        colour.red = sample(0), colour.green = sample(1), colour.blue = sample(2);
      }
      png_set_tRNS(png, info, nullptr, 0, &colour);
    }
    if (v.gamma > 0) png_set_gAMA(png, info, v.gamma);
    if (v.srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    if (v.iccp)
      png_set_iCCP(png, info, "test", PNG_COMPRESSION_TYPE_BASE,
                   reinterpret_cast<png_const_bytep>(profile.data()), png_uint_32(profile.size()));
    if (!texts.empty()) png_set_text(png, info, texts.data(), int(texts.size()));
    if (v.exif) {
      static png_byte exif[] = {'M', 'M', 0, 42, 0, 0, 0, 8, 0, 0};
      png_set_eXIf_1(png, info, sizeof exif, exif);
    }
    png_write_info(png, info);
    if (v.interlaced) png_set_interlace_handling(png);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
  }
  png_destroy_write_struct(&png, &info);
  return out;
}

std::string describe(const Variant& v) {
  return "type " + std::to_string(v.colorType) + " depth " + std::to_string(v.bitDepth) +
         (v.interlaced ? " Adam7" : "") + (v.trns ? " tRNS" : "") +
         (v.gamma > 0 ? " gAMA " + std::to_string(v.gamma) : "") + (v.srgb ? " sRGB" : "") +
         (v.iccp ? " iCCP" : "") + (v.texts.empty() ? "" : " text " + v.texts[0].first) +
         (v.everyCode ? " every code" : "");
}

void compareVariant(const Variant& v) {
  const std::string name = describe(v);
  const Bytes bytes = writePng(v);
  std::string file = name;
  std::replace_if(
      file.begin(), file.end(), [](char c) { return !std::isalnum(c); }, '_');
  const std::string path = (test::tempDir() / (file + ".png")).string();
  writeBytes(path, bytes);
  compareFile(path);
  compareBytes("embedded " + name + ".png", bytes);
}

// The colour types and the depths each allows (PNG specification, table 11.1).
const std::vector<std::pair<int, std::vector<int>>>& layouts() {
  static const std::vector<std::pair<int, std::vector<int>>> kLayouts = {
      {PNG_COLOR_TYPE_GRAY, {1, 2, 4, 8, 16}}, {PNG_COLOR_TYPE_GRAY_ALPHA, {8, 16}},
      {PNG_COLOR_TYPE_RGB, {8, 16}},           {PNG_COLOR_TYPE_RGB_ALPHA, {8, 16}},
      {PNG_COLOR_TYPE_PALETTE, {1, 2, 4, 8}},
  };
  return kLayouts;
}

TEST(PngTexture, EveryLayoutGivesOpenImageIOsFloats) {
  // Each colour type at each depth, with and without Adam7 and tRNS (grey and RGB: a colour
  // made transparent becomes an alpha channel; a palette: its alphas).
  for (const auto& [colorType, depths] : layouts())
    for (int depth : depths)
      for (bool interlaced : {false, true})
        for (bool trns : {false, true}) {
          if (trns && (colorType & PNG_COLOR_MASK_ALPHA)) continue;
          Variant v;
          v.colorType = colorType, v.bitDepth = depth, v.interlaced = interlaced, v.trns = trns;
          v.seed = uint32_t(colorType * 100 + depth * 4 + interlaced * 2 + trns);
          compareVariant(v);
        }
}

TEST(PngTexture, EveryCodeConvertsAsOpenImageIOConvertsIt) {
  // OpenImageIO multiplies by 1/255 (1/65535) in float, which rounds some codes one ulp away
  // from code/255: every 8-bit code and every 16-bit code (big-endian in the file) once.
  Variant eight;
  eight.colorType = PNG_COLOR_TYPE_GRAY, eight.width = 256, eight.height = 1;
  eight.everyCode = true;
  compareVariant(eight);
  Variant sixteen;
  sixteen.colorType = PNG_COLOR_TYPE_GRAY, sixteen.bitDepth = 16, sixteen.width = 256;
  sixteen.height = 256, sixteen.everyCode = true;
  compareVariant(sixteen);
  // The 8-bit ones as Glint has them: code 1 is 1 × float(1/255), not 1/255 rounded.
  const std::string path = (test::tempDir() / "type_0_depth_8_every_code.png").string();
  const Reading r = readWithLibpng(path);
  ASSERT_TRUE(r.ok) << r.error;
  for (int code = 0; code < 256; ++code)
    EXPECT_EQ(r.texels[size_t(code)], float(code) * (1.0f / 255)) << code;
}

TEST(PngTexture, ColourChunksGiveOpenImageIOsColourSpace) {
  // sRGB, or no chunk: "sRGB"; gAMA 1.0: "linear" (Glint then reads the texels as linear);
  // other gAMAs: "Gamma2.2" and the like (read as sRGB); iCCP names none;
  // a text chunk keyed oiio:ColorSpace, in any case, replaces what the chunks said.
  struct Case {
    double gamma;
    bool srgb, iccp;
    std::vector<std::pair<std::string, std::string>> texts;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {0, false, false, {}, "sRGB"},
      {0, true, false, {}, "sRGB"},
      {1.0, false, false, {}, "linear"},
      {1.0 / 2.2, false, false, {}, "Gamma2.2"},
      {0.45455, false, false, {}, "Gamma2.2"},
      {1 / 1.8, false, false, {}, "Gamma1.8"},
      {0.5, false, false, {}, "Gamma2"},
      {0.99999, false, false, {}, "linear"},
      {0, false, true, {}, "sRGB"},
      {1.0, false, true, {}, "linear"},
      {0, false, false, {{"oiio:ColorSpace", "Linear"}}, "Linear"},
      {1.0, false, false, {{"OIIO:COLORSPACE", "sRGB"}}, "sRGB"},
      {0, false, false, {{"oiio:ColorSpace", "lin_rec709"}, {"Comment", "x"}}, "lin_rec709"},
      {0, false, false, {{"ColorSpace", "linear"}}, "sRGB"},
  };
  for (int colorType : {PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_GRAY})
    for (const Case& c : cases) {
      Variant v;
      v.colorType = colorType, v.gamma = c.gamma, v.srgb = c.srgb, v.iccp = c.iccp;
      v.texts = c.texts;
      compareVariant(v);
      for (bool interlaced : {false, true}) {
        v.interlaced = interlaced;
        const Reading r = readBytesWithLibpng("case.png", writePng(v));
        ASSERT_TRUE(r.ok) << describe(v) << ": " << r.error;
        EXPECT_STREQ(r.info.colorspace, c.expected) << describe(v);
      }
    }
}

TEST(PngTexture, ExifAndOtherFormatsAreLeftToOpenImageIO) {
  // Exif may set OpenImageIO's colour space to sRGB (its Exif decoder's rule), and XMP may set
  // oiio:ColorSpace itself: such files, and names or bytes that are not PNG's, go to
  // OpenImageIO as before.
  Variant v;
  v.exif = true;
  EXPECT_TRUE(readBytesWithLibpng("exif.png", writePng(v)).declined);
  v.exif = false;
  v.texts = {{"Raw profile type exif", "exif 10 4d4d002a000000080000"}};
  EXPECT_TRUE(readBytesWithLibpng("exif_text.png", writePng(v)).declined);
  v.texts = {{"XML:com.adobe.xmp",
              "<x:xmpmeta xmlns:x='adobe:ns:meta/'><rdf:RDF "
              "xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#'><rdf:Description "
              "xmlns:oiio='http://openimageio.org/' oiio:ColorSpace='linear'/></rdf:RDF>"
              "</x:xmpmeta>"}};
  EXPECT_TRUE(readBytesWithLibpng("xmp.png", writePng(v)).declined);
  v.texts = {};
  const Bytes png = writePng(v);
  EXPECT_TRUE(readBytesWithLibpng("texture.jpg", png).declined);
  EXPECT_FALSE(readBytesWithLibpng("texture.PNG", png).declined);
  EXPECT_TRUE(readBytesWithLibpng("texture.png", Bytes(png.begin(), png.begin() + 7)).declined);
  Bytes notPng = png;
  notPng[7] = 'x';  // the signature's last byte: OpenImageIO's reader refuses it too
  EXPECT_TRUE(readBytesWithLibpng("texture.png", notPng).declined);
  // The file with Exif still opens, through OpenImageIO.
  v.exif = true;
  const std::string path = (test::tempDir() / "exif_texture.png").string();
  writeBytes(path, writePng(v));
  const auto texture = openImageTexture(path);
  EXPECT_EQ(texture->path(), path);
}

TEST(PngTexture, EveryPngOfTheRepositoryAndAssimpsModelsGivesOpenImageIOsFloats) {
  std::vector<std::string> files = test::filesUnder(GLINT_SOURCE_DIR, {".png"});
  const size_t ours = files.size();
  for (const std::string& f : test::filesUnder("/usr/share/assimp/models", {".png"}))
    files.push_back(f);
  // scenes/assets alone holds 8 (the glTF, cut-out and normal-map assets).
  EXPECT_GE(ours, 8u);
  int compared = 0;
  for (const std::string& path : files) {
    const Reading r = readWithLibpng(path);
    if (r.declined) continue;  // Exif, or not a PNG inside
    test::expectSameReading(kPngReader.library, r, test::readWithOpenImageIO(path), path);
    ++compared;
  }
  EXPECT_GE(compared, int(ours));
  std::printf("compared %d of %zu PNGs\n", compared, files.size());
}

// Damaged files: refused by both readers, or read by both to the same floats; never a crash.
Bytes sampleFile(bool interlaced) {
  Variant v;
  v.colorType = PNG_COLOR_TYPE_RGB_ALPHA, v.interlaced = interlaced, v.gamma = 1.0;
  v.width = 9, v.height = 5;
  return writePng(v);
}

// The chunk `type` with `data`, its length and CRC.
Bytes chunk(const char* type, const Bytes& data) {
  // Sized once and written in place: grown from a 4-byte vector, it drew GCC 12's false
  // -Wstringop-overread and -overflow at the LTO link.
  Bytes c(4 + 4 + data.size() + 4);
  uLong crc = crc32(0, reinterpret_cast<const Bytef*>(type), 4);
  crc = crc32(crc, data.data(), uInt(data.size()));
  for (size_t k = 0; k < 4; ++k) {
    const int shift = 24 - 8 * int(k);
    c[k] = png_byte(data.size() >> shift);
    c[4 + k] = png_byte(type[k]);
    c[8 + data.size() + k] = png_byte(crc >> shift);
  }
  std::copy(data.begin(), data.end(), c.begin() + 8);
  return c;
}

Bytes header(uint32_t width, uint32_t height, int depth, int colorType) {
  const Bytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes ihdr = {png_byte(width >> 24),
                png_byte(width >> 16),
                png_byte(width >> 8),
                png_byte(width),
                png_byte(height >> 24),
                png_byte(height >> 16),
                png_byte(height >> 8),
                png_byte(height),
                png_byte(depth),
                png_byte(colorType),
                0,
                0,
                0};
  Bytes out = signature;
  const Bytes c = chunk("IHDR", ihdr);
  out.insert(out.end(), c.begin(), c.end());
  return out;
}

TEST(PngTexture, TruncatedAndCorruptedFilesAreRefusedAsOpenImageIORefusesThem) {
  // Under AddressSanitizer compared at every eighth file (test::compareDamaged).
  size_t call = 0;
  for (bool interlaced : {false, true}) {
    const Bytes good = sampleFile(interlaced);
    const std::string tag = interlaced ? " (Adam7)" : "";
    // Every length short of the whole file.
    for (size_t n = 8; n < good.size(); ++n)
      test::compareDamaged(kPngReader, "cut at " + std::to_string(n) + tag + ".png",
                           Bytes(good.begin(), good.begin() + long(n)), call++);
    // Every byte after the signature inverted: CRC errors in critical chunks refuse it; in
    // ancillary ones (gAMA) libpng drops the chunk.
    for (size_t i = 8; i < good.size(); ++i) {
      Bytes bad = good;
      bad[i] ^= 0xff;
      test::compareDamaged(kPngReader, "byte " + std::to_string(i) + " inverted" + tag + ".png",
                           bad, call++);
    }
  }
  // Headers libpng refuses: zero or over 2^31 sides, depths a colour type does not allow,
  // unknown colour types; then an image with no IDAT, and data too short for its size.
  const Bytes idat = chunk("IDAT", {0x78, 0x9c, 0x63, 0x00, 0x00, 0x00, 0x01, 0x00, 0x01});
  const Bytes iend = chunk("IEND", {});
  for (const auto& [w, h, depth, type] :
       std::vector<std::array<uint32_t, 4>>{{0, 1, 8, 0},
                                            {1, 0, 8, 0},
                                            {0x80000000u, 1, 8, 0},
                                            {1, 0xffffffffu, 8, 2},
                                            {1, 1, 3, 0},
                                            {1, 1, 16, 3},
                                            {1, 1, 1, 2},
                                            {1, 1, 8, 5},
                                            {1, 1, 8, 7},
                                            {2000000, 1, 8, 0},
                                            {4, 4, 8, 0}}) {
    Bytes file = header(w, h, int(depth), int(type));
    test::append(file, idat);
    test::append(file, iend);
    compareBytes("header " + std::to_string(w) + "x" + std::to_string(h) + " depth " +
                     std::to_string(depth) + " type " + std::to_string(type) + ".png",
                 file);
  }
  Bytes noIdat = header(4, 4, 8, 0);
  test::append(noIdat, iend);
  compareBytes("no IDAT.png", noIdat);
  // A palette image without its PLTE.
  Bytes noPalette = header(1, 1, 8, 3);
  test::append(noPalette, idat);
  test::append(noPalette, iend);
  compareBytes("no PLTE.png", noPalette);
}

TEST(PngTexture, AHostileFileIsRefusedNamingTheFileAndWhatWasWrong) {
  // Through the texture reader itself: the file named, and libpng's reason.
  const Bytes good = sampleFile(false);
  const std::string cut = (test::tempDir() / "cut.png").string();
  writeBytes(cut, Bytes(good.begin(), good.begin() + long(good.size() - 30)));
  test::expectRefusedNaming(cut, "invalid PNG data");
  // A header declaring 1,000,000 x 1,000,000 (libpng's largest) is refused by the image limits
  // before any row is read or allocated (film/image_limits.h): 4 TB of float texels.
  Bytes huge = header(1000000, 1000000, 8, 0);
  test::append(huge, chunk("IDAT", {0x78, 0x9c, 0x03, 0x00}));
  test::append(huge, chunk("IEND", {}));
  const std::string hugePath = (test::tempDir() / "huge.png").string();
  writeBytes(hugePath, huge);
  test::expectRefusedNaming(hugePath, "1000000x1000000");
}

TEST(PngTexture, ACompressedTextBombIsDroppedWithinLibpngsChunkLimit) {
  // A zTXt chunk inflating to 64 MB: libpng stops at its 8 MB chunk limit and drops the chunk
  // (a benign error), as for OpenImageIO; the image reads the same.
  Variant v;
  Bytes file = writePng(v);
  std::string zeros(64u << 20, '\0');
  uLongf size = compressBound(uLong(zeros.size()));
  Bytes packed(size);
  ASSERT_EQ(compress2(packed.data(), &size, reinterpret_cast<const Bytef*>(zeros.data()),
                      uLong(zeros.size()), 9),
            Z_OK);
  packed.resize(size);
  Bytes data = {'b', 'o', 'm', 'b', 0, 0};
  test::append(data, packed);
  const Bytes ztxt = chunk("zTXt", data);
  file.insert(file.begin() + 33, ztxt.begin(), ztxt.end());  // after the signature and IHDR
  compareBytes("text bomb.png", file);
  EXPECT_TRUE(readBytesWithLibpng("text bomb.png", file).ok);
}

TEST(PngTexture, AChunkDeclaringMoreThanTheFileHoldsIsRefusedBeforeItIsAllocated) {
  // A tEXt chunk whose length says 1.3 GB in a file of 100 bytes (the texture fuzzer's find):
  // libpng only warns that it is past its 8 MB limit, then allocated and zeroed 1.3 GB before it
  // found the file's end (5.9 s, 1.3 GB, through OpenImageIO as well). Glint's allocator refuses
  // anything past 64 MB: the file is refused at once, naming the size.
  const Bytes good = sampleFile(false);
  // The signature and IHDR, then a tEXt chunk's length (1 296 891 965 bytes), type and key.
  Bytes file(good.begin(), good.begin() + 33);
  test::append(file, {0x4d, 0x4d, 0x00, 0x3d, 't', 'E', 'X', 't', 'k', 'e', 'y'});
  const Reading r = readBytesWithLibpng("huge chunk.png", file);
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("a chunk that would take 1296891966 bytes (at most 64 MB)"),
            std::string::npos)
      << r.error;
}

}  // namespace
}  // namespace glint
