#pragma once
// Writes the 8- and 16-bit images people look at (display images, difference images). PNG goes
// through libpng; the other formats (.jpg, .tif) through OpenImageIO, which is loaded only then
// (film/oiio_module.h): its ~260 shared libraries cost a run 0.3 s and 130 MB before main().
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

// Writes width × height RGB pixels of `codes` (interleaved code values of `bits` = 8 or 16 bits)
// atomically (film/atomic_file.h); the format comes from the extension of `path`. Throws
// GlintError naming the file when it cannot be written.
void writeRgbImage(const std::string& path, int width, int height, int bits,
                   const std::vector<uint16_t>& codes);

}  // namespace glint
