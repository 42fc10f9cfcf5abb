#pragma once
// OpenImageIO behind a module loaded at run time. Debian's libOpenImageIO pulls in about 260
// shared libraries (ffmpeg, GDAL, OpenCV, ...): linked into glint, they cost every run 0.3 s and
// 130 MB before main(). Only the runs that need what only OpenImageIO does (display images other
// than EXR and PNG, textures other than PNG, JPEG and Radiance HDR) load libglint_oiio.so, and with
// it OpenImageIO. One loader serves film/'s image output and io/'s texture input
// (io/texture_file.h), so it sits in film/, the lower of the two: both reach it downward, and the
// process loads the module once.
#include <cstdint>
#include <string>
#include <vector>

#include "film/oiio_module_abi.h"

namespace glint::oiio_module {

// Writes width × height pixels of `channels` code values of `bits` (8 or 16) to `tmpPath` in
// the format of `path`'s extension. Throws GlintError naming `path` when the module cannot be
// loaded or OpenImageIO cannot write it.
void writeImage(const std::string& path, const std::string& tmpPath, int width, int height,
                int channels, int bits, const std::vector<uint16_t>& codes);

// OpenImageIO's image readers for textures (io/texture_file.h). Throws GlintError naming the
// texture `path` when the module cannot be loaded.
struct TextureFunctions {
  GlintOiioTextureOpen open = nullptr;
  GlintOiioTextureOpenMemory openMemory = nullptr;
  GlintOiioTextureRead read = nullptr;
  GlintOiioTextureClose close = nullptr;
};
const TextureFunctions& textureFunctions(const std::string& path);

// Where the module is looked for: beside the executable (../lib/glint/), then in the build tree.
std::vector<std::string> searchPath();

}  // namespace glint::oiio_module
