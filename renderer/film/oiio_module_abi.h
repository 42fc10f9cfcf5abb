#pragma once
// The C interface between glint and libglint_oiio.so (film/oiio_module.h): plain types only, so
// that the module and the program share no C++ ABI beyond this.
#include <cstddef>

extern "C" {
// Returns 0 on success; otherwise writes a message of at most `errorSize` bytes to `error`.
// `formatPath` names the format by its extension; the data go to `path`.
using GlintOiioWriteImage = int (*)(const char* formatPath, const char* path, int width, int height,
                                    int channels, int bits, const void* pixels, char* error,
                                    size_t errorSize);
}

inline constexpr const char* kGlintOiioModuleName = "libglint_oiio.so";
inline constexpr const char* kGlintOiioWriteImageSymbol = "glint_oiio_write_image";
