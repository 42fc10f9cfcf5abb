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

// Image textures: OpenImageIO reads the file; Glint keeps the texels and filters them
// (materials/mip_pyramid.h).
struct GlintOiioTextureInfo {
  int width, height, channels;
  int isFloat;          // half or float texels (scene-linear by convention)
  int bytesPerChannel;  // of the file's texels: 1 (8-bit), 2 (16-bit, half), 4 (float)
  char colorspace[64];  // the file's oiio:ColorSpace, or empty
  int tileHeight;       // rows of a tiled file's tiles (reads start at a multiple), else 0
};
// Opens `path` with OpenImageIO's reader of `format` (its name: "tiff", "openexr", ...) and no
// other, and fills `info` from its header; returns its handle, or null with a message.
using GlintOiioTextureOpen = void* (*)(const char* path, const char* format,
                                       GlintOiioTextureInfo* info, char* error, size_t errorSize);
// The same for an image held in memory (an FBX's embedded image), which `name` names; the bytes
// must outlive the handle.
using GlintOiioTextureOpenMemory = void* (*)(const char* name, const char* format,
                                             const void* bytes, size_t size,
                                             GlintOiioTextureInfo* info, char* error,
                                             size_t errorSize);
// The texels of rows [y0, y1) (y0 a multiple of tileHeight, y1 too or the height) of an
// opened image's first (full-resolution) level, `channels`
// floats each from channel 0 (integer texels as code / max code), colours not premultiplied by
// alpha, into out (width × (y1 − y0) × channels); returns 0, or nonzero with OpenImageIO's
// message when its reader reported any error (a truncated file must be refused, not rendered
// black).
using GlintOiioTextureRead = int (*)(void* handle, int y0, int y1, int channels, float* out,
                                     char* error, size_t errorSize);
// Closes an opened image (null: nothing).
using GlintOiioTextureClose = void (*)(void* handle);
}

inline constexpr const char* kGlintOiioModuleName = "libglint_oiio.so";
inline constexpr const char* kGlintOiioWriteImageSymbol = "glint_oiio_write_image";
inline constexpr const char* kGlintOiioTextureOpenSymbol = "glint_oiio_texture_open";
inline constexpr const char* kGlintOiioTextureOpenMemorySymbol = "glint_oiio_texture_open_memory";
inline constexpr const char* kGlintOiioTextureReadSymbol = "glint_oiio_texture_read";
inline constexpr const char* kGlintOiioTextureCloseSymbol = "glint_oiio_texture_close";
