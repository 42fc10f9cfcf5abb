#pragma once
// Writes the 8- and 16-bit images people look at (display images, difference images). PNG goes
// through libpng; the other formats (.jpg, .tif) through OpenImageIO, which is loaded only then
// (film/oiio_module.h): its ~260 shared libraries cost a run 0.3 s and 130 MB before main().
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

// Which display a PNG's code values were made for, as its colour chunks say it
// (docs/output.md, Display images): none, the sRGB chunk (with the gAMA and cHRM it implies), or
// a cICP chunk (ITU-T H.273 codes) with cHRM and gAMA for readers that predate cICP.
struct ColourTag {
  enum class Kind { None, Srgb, Cicp } kind = Kind::None;
  uint8_t primaries = 0, transfer = 0;     // H.273 ColourPrimaries, TransferCharacteristics
  std::array<double, 8> chromaticities{};  // white x y, red x y, green x y, blue x y (cHRM)
  double encodingGamma = 0;                // gAMA: the encoding exponent (1/2.2 for sRGB-like)
};

// Interleaved code values, `channels` (3: RGB, 4: RGB and straight alpha) of `bits` (8 or 16).
struct CodeImage {
  int width = 0, height = 0, channels = 3, bits = 8;
  std::vector<uint16_t> codes;
  ColourTag tag;  // written into PNGs; other formats carry none
};

// Writes `image` atomically (film/atomic_file.h); the format comes from the extension of
// `path` (film/image_format.h, checked by the caller). Throws GlintError naming the file when
// it cannot be written.
void writeCodeImage(const std::string& path, const CodeImage& image);

// Width × height RGB pixels of `codes` (interleaved code values of `bits` = 8 or 16 bits), no
// colour tag.
void writeRgbImage(const std::string& path, int width, int height, int bits,
                   const std::vector<uint16_t>& codes);

}  // namespace glint
