#include "film/image_file.h"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdio>

#include "core/error.h"
#include "core/file_names.h"
#include "film/atomic_file.h"
#include "film/oiio_module.h"

namespace glint {

namespace {

constexpr size_t kPngErrorSize = 256;  // the message buffer libpng's errors are copied into

void storePngError(png_structp png, png_const_charp message) {
  auto* error = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(error, kPngErrorSize, "%s", message);
  png_longjmp(png, 1);
}

void ignorePngWarning(png_structp, png_const_charp) {}

// Asks libpng to write the cICP chunk, which libpng 1.6.39 does not know, as an unknown chunk
// before PLTE and IDAT (where the PNG specification, third edition, puts it): colour
// primaries, transfer characteristics, matrix coefficients 0 (RGB) and full range 1.
void addCicpChunk(png_structp png, png_infop info, const ColourTag& tag) {
  static const png_byte kName[5] = {'c', 'I', 'C', 'P', 0};
  // cICP's fourth letter is upper case (not safe to copy): libpng writes it only when told to.
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, kName, 1);
  png_byte data[4] = {tag.primaries, tag.transfer, 0, 1};
  png_unknown_chunk chunk{};
  for (int i = 0; i < 5; ++i) chunk.name[i] = kName[i];
  chunk.data = data;
  chunk.size = sizeof data;
  chunk.location = PNG_HAVE_IHDR;
  png_set_unknown_chunks(png, info, &chunk, 1);
}

void setColourTag(png_structp png, png_infop info, const ColourTag& tag) {
  if (tag.kind == ColourTag::Kind::Srgb) {
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  } else if (tag.kind == ColourTag::Kind::Cicp) {
    const auto& c = tag.chromaticities;
    png_set_cHRM(png, info, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]);
    if (tag.encodingGamma > 0) png_set_gAMA(png, info, tag.encodingGamma);
    addCicpChunk(png, info, tag);
  }
}

// libpng reports errors by longjmp: nothing with a destructor may live in this frame. The
// settings are what OpenImageIO used before (zlib level 6 with its default strategy, libpng's
// adaptive filters, an oFFs chunk of (0, 0)): the same pixels give the same bytes.
bool writePngRows(std::FILE* file, const CodeImage& image, unsigned char** rows, char* error) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, error, storePngError, ignorePngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
               image.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  setColourTag(png, info, image.tag);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

void writePng(const std::string& path, const std::string& tmp, const CodeImage& image) {
  std::vector<unsigned char> bytes(image.codes.begin(), image.codes.end());
  std::vector<unsigned char*> rows(static_cast<size_t>(image.height));
  const size_t rowBytes = size_t(image.width) * size_t(image.channels);
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = &bytes[y * rowBytes];
  std::FILE* file = std::fopen(tmp.c_str(), "wb");
  if (!file) throw GlintError("cannot write " + path + ": cannot create the file");
  char error[kPngErrorSize] = "an I/O error";
  const bool written = writePngRows(file, image, rows.data(), error);
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) throw GlintError("cannot write " + path + ": " + error);
}

}  // namespace

void writeCodeImage(const std::string& path, const CodeImage& image) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    if (lowerExtension(path) == ".png" && image.bits == 8)
      writePng(path, tmp, image);
    else
      oiio_module::writeImage(path, tmp, image.width, image.height, image.channels, image.bits,
                              image.codes);
  });
}

void writeRgbImage(const std::string& path, int width, int height, int bits,
                   const std::vector<uint16_t>& codes) {
  writeCodeImage(path, CodeImage{width, height, 3, bits, codes, {}});
}

}  // namespace glint
