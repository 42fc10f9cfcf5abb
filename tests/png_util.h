#pragma once
// Reading PNGs back with libpng in tests: the header, the 8-bit samples and the colour chunks
// (sRGB, gAMA, cHRM, and cICP, which libpng 1.6.39 reads only as an unknown chunk).
#include <png.h>

#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace glint::test {

struct PngFile {
  bool ok = false;
  std::string signature;  // the first 8 bytes
  png_uint_32 width = 0, height = 0;
  int colorType = -1, bitDepth = 0, channels = 0;
  std::vector<unsigned char> samples;         // rows top-down, interleaved
  std::optional<int> srgbIntent;              // sRGB chunk
  std::optional<double> gamma;                // gAMA
  std::optional<std::array<double, 8>> chrm;  // cHRM: white, red, green, blue (x, y)
  std::optional<std::array<int, 4>> cicp;     // cICP: primaries, transfer, matrix, full range
};

inline PngFile readPng(const std::string& path) {
  PngFile f;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return f;
  char sig[8] = {};
  f.signature.assign(sig, std::fread(sig, 1, 8, file));
  std::rewind(file);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    f.ok = false;
    return f;
  }
  png_init_io(png, file);
  static const png_byte kCicp[5] = {'c', 'I', 'C', 'P', 0};
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, kCicp, 1);
  png_read_info(png, info);
  int interlace = 0, compression = 0, filter = 0;
  png_get_IHDR(png, info, &f.width, &f.height, &f.bitDepth, &f.colorType, &interlace, &compression,
               &filter);
  f.channels = png_get_channels(png, info);
  int intent = 0;
  if (png_get_sRGB(png, info, &intent)) f.srgbIntent = intent;
  double gamma = 0;
  if (png_get_gAMA(png, info, &gamma)) f.gamma = gamma;
  std::array<double, 8> c{};
  if (png_get_cHRM(png, info, &c[0], &c[1], &c[2], &c[3], &c[4], &c[5], &c[6], &c[7])) f.chrm = c;
  png_unknown_chunkp chunks = nullptr;
  const int n = png_get_unknown_chunks(png, info, &chunks);
  for (int i = 0; i < n; ++i)
    if (std::string(reinterpret_cast<const char*>(chunks[i].name), 4) == "cICP" &&
        chunks[i].size == 4)
      f.cicp = std::array<int, 4>{chunks[i].data[0], chunks[i].data[1], chunks[i].data[2],
                                  chunks[i].data[3]};
  const size_t rowBytes = png_get_rowbytes(png, info);
  f.samples.resize(rowBytes * f.height);
  std::vector<png_bytep> rows(f.height);
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = f.samples.data() + y * rowBytes;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(file);
  f.ok = true;
  return f;
}

inline const std::string kPngSignature = "\x89PNG\r\n\x1a\n";

}  // namespace glint::test
