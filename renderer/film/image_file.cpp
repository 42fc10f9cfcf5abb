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

// libpng reports errors by longjmp: nothing with a destructor may live in this frame. The
// settings are what OpenImageIO used before (zlib level 6 with its default strategy, libpng's
// adaptive filters, an oFFs chunk of (0, 0)): the same pixels give the same bytes.
bool writePngRows(std::FILE* file, int width, int height, unsigned char** rows, char* error) {
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
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

void writePng(const std::string& path, const std::string& tmp, int width, int height,
              const std::vector<uint16_t>& codes) {
  std::vector<unsigned char> bytes(codes.begin(), codes.end());
  std::vector<unsigned char*> rows(static_cast<size_t>(height));
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = &bytes[y * size_t(width) * 3];
  std::FILE* file = std::fopen(tmp.c_str(), "wb");
  if (!file) throw GlintError("cannot write " + path + ": cannot create the file");
  char error[kPngErrorSize] = "an I/O error";
  const bool written = writePngRows(file, width, height, rows.data(), error);
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) throw GlintError("cannot write " + path + ": " + error);
}

}  // namespace

void writeRgbImage(const std::string& path, int width, int height, int bits,
                   const std::vector<uint16_t>& codes) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    if (lowerExtension(path) == ".png" && bits == 8)
      writePng(path, tmp, width, height, codes);
    else
      oiio_module::writeImage(path, tmp, width, height, 3, bits, codes);
  });
}

}  // namespace glint
