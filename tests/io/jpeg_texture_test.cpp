// JPEG textures read by libjpeg (io/jpeg_texture.h) against OpenImageIO's JPEG reader, which read
// them before: the same header, oiio:ColorSpace and floats, bit for bit, for every JPEG in the
// repository and Assimp's test models and for JPEGs written here in every layout libjpeg makes
// (grey, RGB, YCbCr at each chroma subsampling, progressive, arithmetic-coded, with restart
// markers and metadata); the same refusals for damaged files; and the bounds OpenImageIO lacks.
#include "io/jpeg_texture.h"

#include <gtest/gtest.h>

// clang-format off
#include <cstdio>
#include <jpeglib.h>
// clang-format on

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdlib>
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

// A JPEG to write: its layout and (random, smoothed) samples.
struct Variant {
  int width = 13, height = 7;       // not multiples of the 8- or 16-texel blocks
  int components = 3;               // 1 (grey), 3 or 4
  J_COLOR_SPACE space = JCS_YCbCr;  // as stored: JCS_GRAYSCALE, JCS_YCbCr, JCS_RGB or JCS_CMYK
  int lumaH = 1, lumaV = 1;         // the first component's sampling factors (chroma's are 1)
  bool progressive = false, arithmetic = false;
  int restartRows = 0;
  int quality = 90;
  std::vector<std::pair<int, std::string>> markers;  // (marker, data) written after the header
  std::vector<jpeg_scan_info> scans;                 // a scan script of its own
  uint32_t seed = 1;
};

struct WriteErrors {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
};

void failWrite(j_common_ptr c) {
  char text[JMSG_LENGTH_MAX];
  (*c->err->format_message)(c, text);
  ADD_FAILURE() << "libjpeg cannot write the test JPEG: " << text;
  std::longjmp(reinterpret_cast<WriteErrors*>(c->err)->jump, 1);
}

// libjpeg calls (no object with a destructor may live across its longjmp): `v` compressed into
// `*out` (malloc'ed by libjpeg).
void compress(const Variant& v, const unsigned char* samples, unsigned char** out,
              unsigned long* size) {
  jpeg_compress_struct c{};
  WriteErrors errors{};
  c.err = jpeg_std_error(&errors.pub);
  errors.pub.error_exit = failWrite;
  if (setjmp(errors.jump) == 0) {
    jpeg_create_compress(&c);
    jpeg_mem_dest(&c, out, size);
    c.image_width = JDIMENSION(v.width);
    c.image_height = JDIMENSION(v.height);
    c.input_components = v.components;
    c.in_color_space = v.components == 1 ? JCS_GRAYSCALE : v.components == 4 ? JCS_CMYK : JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_colorspace(&c, v.space);
    jpeg_set_quality(&c, v.quality, TRUE);
    c.comp_info[0].h_samp_factor = v.lumaH;
    c.comp_info[0].v_samp_factor = v.lumaV;
    for (int k = 1; k < v.components; ++k)
      c.comp_info[k].h_samp_factor = c.comp_info[k].v_samp_factor = 1;
    if (v.progressive) jpeg_simple_progression(&c);
    if (!v.scans.empty()) {
      c.scan_info = v.scans.data();
      c.num_scans = int(v.scans.size());
    }
    c.arith_code = v.arithmetic ? TRUE : FALSE;
    c.restart_in_rows = v.restartRows;
    jpeg_start_compress(&c, TRUE);
    for (const auto& [marker, data] : v.markers)
      jpeg_write_marker(&c, marker, reinterpret_cast<const JOCTET*>(data.data()),
                        unsigned(data.size()));
    const size_t rowBytes = size_t(v.width) * size_t(v.components);
    while (c.next_scanline < c.image_height) {
      JSAMPROW row = const_cast<JSAMPROW>(samples + c.next_scanline * rowBytes);
      jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
  }
  jpeg_destroy_compress(&c);
}

Bytes writeJpeg(const Variant& v) {
  // Random walks along each row, so that the blocks hold more than noise.
  std::vector<unsigned char> samples(size_t(v.width) * size_t(v.height) * size_t(v.components));
  std::mt19937 random(v.seed);
  int value = 128;
  for (unsigned char& s : samples) {
    value = std::clamp(value + int(random() % 41) - 20, 0, 255);
    s = static_cast<unsigned char>(value);
  }
  unsigned char* out = nullptr;
  unsigned long size = 0;
  compress(v, samples.data(), &out, &size);
  Bytes bytes(out, out + size);
  std::free(out);
  return bytes;
}

void compareFile(const std::string& path) { test::compareFile(kJpegReader, path); }

void compareBytes(const std::string& name, const Bytes& bytes) {
  test::compareBytes(kJpegReader, name, bytes);
}

// Written to a file and compared from it and from memory.
void compareVariant(const std::string& name, const Variant& v) {
  const Bytes bytes = writeJpeg(v);
  ASSERT_FALSE(bytes.empty()) << name;
  const std::string path = (test::tempDir() / (name + ".jpg")).string();
  writeBytes(path, bytes);
  compareFile(path);
  compareBytes("embedded " + name + ".jpg", bytes);
}

TEST(JpegTexture, EveryJpegOfTheRepositoryAndAssimpsModelsGivesOpenImageIOsFloats) {
  const std::vector<std::string> extensions = {".jpg", ".jpeg", ".jpe", ".jif", ".jfif", ".jfi"};
  std::vector<std::string> files = test::filesUnder(GLINT_SOURCE_DIR, extensions);
  const size_t ours = files.size();
  for (const std::string& f : test::filesUnder("/usr/share/assimp/models", extensions))
    files.push_back(f);
  // scenes/assets/spider alone holds 5 (baseline and progressive).
  EXPECT_GE(ours, 5u);
  int compared = 0;
  for (const std::string& path : files) {
    const Reading r = test::readWith(kJpegReader, path);
    if (r.declined) continue;  // XMP, CMYK, or not a JPEG inside
    test::expectSameReading(kJpegReader.library, r, test::readWithOpenImageIO(path), path);
    ++compared;
  }
  EXPECT_GE(compared, int(ours));
  std::printf("compared %d of %zu JPEGs\n", compared, files.size());
}

TEST(JpegTexture, EveryLayoutGivesOpenImageIOsFloats) {
  struct Case {
    const char* name;
    int components;
    J_COLOR_SPACE space;
    int lumaH, lumaV;
  };
  // Grey; RGB stored as RGB; YCbCr at 4:4:4, 4:2:2, 4:2:0, 4:4:0 and 4:1:1.
  const Case cases[] = {{"grey", 1, JCS_GRAYSCALE, 1, 1}, {"rgb", 3, JCS_RGB, 1, 1},
                        {"ycc444", 3, JCS_YCbCr, 1, 1},   {"ycc422", 3, JCS_YCbCr, 2, 1},
                        {"ycc420", 3, JCS_YCbCr, 2, 2},   {"ycc440", 3, JCS_YCbCr, 1, 2},
                        {"ycc411", 3, JCS_YCbCr, 4, 1}};
  uint32_t seed = 1;
  for (const Case& c : cases)
    for (bool progressive : {false, true})
      for (bool arithmetic : {false, true})
        for (const auto& [width, height] : {std::pair{13, 7}, std::pair{1, 1}, std::pair{40, 33}}) {
          Variant v;
          v.components = c.components, v.space = c.space, v.lumaH = c.lumaH, v.lumaV = c.lumaV;
          v.progressive = progressive, v.arithmetic = arithmetic;
          v.width = width, v.height = height, v.seed = seed++;
          v.restartRows = width > 20 ? 1 : 0;  // restart markers in the larger ones
          compareVariant(std::string(c.name) + (progressive ? "_progressive" : "") +
                             (arithmetic ? "_arithmetic" : "") + "_" + std::to_string(width) + "x" +
                             std::to_string(height),
                         v);
        }
}

TEST(JpegTexture, EveryCodeConvertsAsOpenImageIOConvertsIt) {
  // A grey JPEG at quality 100 keeps most codes; each comes out as code × float(1/255), which
  // rounds some codes one ulp away from code / 255 (OpenImageIO's convert_type).
  Variant v;
  v.components = 1, v.space = JCS_GRAYSCALE, v.width = 256, v.height = 16, v.quality = 100;
  const Bytes bytes = writeJpeg(v);
  compareBytes("every code.jpg", bytes);
  const Reading r = test::readBytesWith(kJpegReader, "every code.jpg", bytes);
  ASSERT_TRUE(r.ok) << r.error;
  int different = 0;
  for (float t : r.texels) {
    const float code = std::nearbyint(t * 255);
    EXPECT_EQ(t, code * (1.0f / 255)) << t;
    different += t != code / 255;
  }
  EXPECT_GT(different, 0);  // the sample reaches codes where the two roundings differ
}

// An APP1 marker holding a big-endian Exif block with one tag, ColorSpace (0xa001) = `value`.
std::string exifWithColorSpace(int value) {
  const unsigned char block[] = {'E',
                                 'x',
                                 'i',
                                 'f',
                                 0,
                                 0,
                                 'M',
                                 'M',
                                 0,
                                 42,
                                 0,
                                 0,
                                 0,
                                 8,
                                 0,
                                 1,  // one entry
                                 0xa0,
                                 0x01,
                                 0,
                                 3,
                                 0,
                                 0,
                                 0,
                                 1,
                                 uint8_t(value >> 8),
                                 uint8_t(value),
                                 0,
                                 0,
                                 0,
                                 0,
                                 0,
                                 0};
  return std::string(reinterpret_cast<const char*>(block), sizeof block);
}

// A minimal RGB ICC profile: header only, no tags.
std::string iccProfile() {
  std::string p(132, '\0');
  p[3] = char(132);
  std::memcpy(&p[12], "mntr", 4);
  std::memcpy(&p[16], "RGB ", 4);
  std::memcpy(&p[20], "XYZ ", 4);
  std::memcpy(&p[36], "acsp", 4);
  return p;
}

// Photoshop's APP13 with an empty IPTC block (resource 1028), whole as OpenImageIO reads it.
std::string photoshopIptc() {
  return std::string(
      "Photoshop 3.0\0"
      "8BIM\x04\x04\0\0\0\0\0\0",
      26);
}

TEST(JpegTexture, MetadataGivesOpenImageIOsColourSpaceOrIsLeftToIt) {
  // Exif (sRGB, or uncalibrated), an ICC profile (APP2), a comment, Photoshop's APP13: sRGB, as
  // OpenImageIO says. XMP may set oiio:ColorSpace itself, and CMYK is converted by OpenImageIO:
  // those, and names or bytes that are not JPEG's, go to OpenImageIO.
  const std::string icc = std::string("ICC_PROFILE\0\x01\x01", 14) + iccProfile();
  const std::vector<std::pair<std::string, std::vector<std::pair<int, std::string>>>> kept = {
      {"exif_srgb", {{JPEG_APP0 + 1, exifWithColorSpace(1)}}},
      {"exif_uncalibrated", {{JPEG_APP0 + 1, exifWithColorSpace(0xffff)}}},
      {"icc", {{JPEG_APP0 + 2, icc}}},
      {"comment", {{JPEG_COM, "a comment"}}},
      {"photoshop", {{JPEG_APP0 + 13, photoshopIptc()}}}};
  for (const auto& [name, markers] : kept) {
    Variant v;
    v.markers = markers;
    compareVariant(name, v);
    const Reading r = test::readBytesWith(kJpegReader, name + ".jpg", writeJpeg(v));
    ASSERT_TRUE(r.ok) << name << ": " << r.error;
    EXPECT_STREQ(r.info.colorspace, "sRGB") << name;
  }
  Variant xmp;
  xmp.markers = {{JPEG_APP0 + 1,
                  std::string("http://ns.adobe.com/xap/1.0/\0", 29) +
                      "<x:xmpmeta xmlns:x='adobe:ns:meta/'><rdf:RDF "
                      "xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#'><rdf:Description "
                      "xmlns:oiio='http://openimageio.org/' oiio:ColorSpace='linear'/></rdf:RDF>"
                      "</x:xmpmeta>"}};
  EXPECT_TRUE(test::readBytesWith(kJpegReader, "xmp.jpg", writeJpeg(xmp)).declined);
  Variant cmyk;
  cmyk.components = 4, cmyk.space = JCS_CMYK;
  EXPECT_TRUE(test::readBytesWith(kJpegReader, "cmyk.jpg", writeJpeg(cmyk)).declined);
  cmyk.space = JCS_YCCK;
  EXPECT_TRUE(test::readBytesWith(kJpegReader, "ycck.jpg", writeJpeg(cmyk)).declined);
  const Bytes jpeg = writeJpeg(Variant{});
  EXPECT_TRUE(test::readBytesWith(kJpegReader, "texture.png", jpeg).declined);
  for (const char* name : {"t.JPG", "t.jpeg", "t.jpe", "t.jif", "t.jfif", "t.jfi"})
    EXPECT_FALSE(test::readBytesWith(kJpegReader, name, jpeg).declined) << name;
  EXPECT_TRUE(
      test::readBytesWith(kJpegReader, "t.jpg", Bytes(jpeg.begin(), jpeg.begin() + 1)).declined);
  Bytes notJpeg = jpeg;
  notJpeg[1] = 0xd9;
  EXPECT_TRUE(test::readBytesWith(kJpegReader, "t.jpg", notJpeg).declined);
  // The XMP file still opens, through OpenImageIO.
  const std::string path = (test::tempDir() / "xmp_texture.jpg").string();
  writeBytes(path, writeJpeg(xmp));
  EXPECT_EQ(openImageTexture(path)->path(), path);
}

TEST(JpegTexture, TruncatedAndCorruptedFilesAreRefusedAsOpenImageIORefusesThem) {
  // Every length short of the whole file, and every byte inverted: both readers refuse it
  // (libjpeg's errors, and its warnings, which OpenImageIO reports as errors), or both read the
  // same floats (under AddressSanitizer compared at every eighth file: test::compareDamaged).
  size_t call = 0;
  for (bool progressive : {false, true}) {
    Variant v;
    v.width = 9, v.height = 5, v.lumaH = 2, v.lumaV = 2, v.quality = 75;
    v.progressive = progressive;
    const Bytes good = writeJpeg(v);
    const std::string tag = progressive ? " (progressive)" : "";
    for (size_t n = 2; n < good.size(); ++n)
      test::compareDamaged(kJpegReader, "cut at " + std::to_string(n) + tag + ".jpg",
                           Bytes(good.begin(), good.begin() + long(n)), call++);
    for (size_t i = 2; i < good.size(); ++i) {
      Bytes bad = good;
      bad[i] ^= 0xff;
      test::compareDamaged(kJpegReader, "byte " + std::to_string(i) + " inverted" + tag + ".jpg",
                           bad, call++);
    }
  }
  std::printf("%zu damaged files\n", call);
}

// The offset of the first SOF marker's height (its size follows: height, then width, 16 bits
// big-endian each).
size_t frameSizeOffset(const Bytes& jpeg) {
  for (size_t i = 2; i + 9 < jpeg.size(); ++i)
    if (jpeg[i] == 0xff && (jpeg[i + 1] == 0xc0 || jpeg[i + 1] == 0xc2)) return i + 5;
  return 0;
}

TEST(JpegTexture, AHostileFileIsRefusedNamingTheFileAndWhatWasWrong) {
  // Through the texture reader itself: the file named, and libjpeg's reason.
  const Bytes good = writeJpeg(Variant{});
  const std::string cut = (test::tempDir() / "cut.jpg").string();
  writeBytes(cut, Bytes(good.begin(), good.begin() + long(good.size() / 2)));
  test::expectRefusedNaming(cut, "invalid JPEG data");
  // A header declaring 65500 x 65500 (JPEG's largest) over a few bytes of data is refused by
  // the memory budget before any row is decoded: 68 GB of float texels with their pyramid.
  for (bool progressive : {false, true}) {
    Variant v;
    v.progressive = progressive;
    Bytes huge = writeJpeg(v);
    const size_t at = frameSizeOffset(huge);
    ASSERT_GT(at, 0u);
    huge[at] = huge[at + 2] = 0xff;
    huge[at + 1] = huge[at + 3] = 0xdc;
    const std::string path = (test::tempDir() / "huge.jpg").string();
    writeBytes(path, huge);
    test::expectRefusedNaming(path, "65500x65500");
  }
}

// A progressive scan script of `components` components that sends every coefficient of each
// component one bit at a time from bit 10 (libjpeg's deepest point transform for 8-bit
// samples): per component 64 first scans and 64 × 10 refinements.
std::vector<jpeg_scan_info> bitByBitScans(int components) {
  std::vector<jpeg_scan_info> scans;
  for (int c = 0; c < components; ++c)
    for (int k = 0; k < 64; ++k)
      for (int ah = 0, al = 10; al >= 0; ah = al, --al) {
        jpeg_scan_info s{};
        s.comps_in_scan = 1;
        s.component_index[0] = c;
        s.Ss = s.Se = k;
        s.Ah = ah;
        s.Al = al;
        scans.push_back(s);
      }
  return scans;
}

TEST(JpegTexture, AFileOfMoreScansThanAnyEncoderWritesIsRefused) {
  // Each scan of a progressive file passes over the whole image: a small file of many scans
  // makes a large image's decoding run for minutes. 704 scans (a grey image sent bit by bit)
  // are read as OpenImageIO reads them; 2112 (three components) are past kMaxScans and refused,
  // where OpenImageIO decodes them all.
  static_assert(jpeg_texture::kMaxScans > 704 && jpeg_texture::kMaxScans < 2112);
  Variant grey;
  grey.components = 1, grey.space = JCS_GRAYSCALE, grey.scans = bitByBitScans(1);
  compareVariant("704 scans", grey);
  Variant colour;
  colour.space = JCS_YCbCr, colour.scans = bitByBitScans(3);
  const Reading r = test::readBytesWith(kJpegReader, "2112 scans.jpg", writeJpeg(colour));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("more than 1000 scans"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace glint
