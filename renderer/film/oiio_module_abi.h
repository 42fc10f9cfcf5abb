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

// Image textures through OpenImageIO's TextureSystem (one per process, in the module).
struct GlintOiioTextureInfo {
  int width, height, channels;
  int isFloat;          // half or float texels (scene-linear by convention)
  int bytesPerChannel;  // of the file's texels: 1 (8-bit), 2 (16-bit, half), 4 (float)
  char colorspace[64];  // the file's oiio:ColorSpace, or empty
};
// Opens `path` as a texture and fills `info`; returns its handle, or null with a message.
using GlintOiioTextureOpen = void* (*)(const char* path, GlintOiioTextureInfo* info, char* error,
                                       size_t errorSize);
// The same for an image held in memory (a glTF file's embedded PNG or JPEG): `name` ends in the
// format's extension; the module keeps a copy of the bytes for the process's life.
using GlintOiioTextureOpenMemory = void* (*)(const char* name, const void* bytes, size_t size,
                                             GlintOiioTextureInfo* info, char* error,
                                             size_t errorSize);
// Reads the texels of an opened texture (one lookup at its centre, which reads the file and
// builds its MIP levels): returns 0, or nonzero with OpenImageIO's message when it reported any
// error while reading (a failed read must stop the load, not render black or wait for ever).
using GlintOiioTextureLoad = int (*)(void* handle, int channels, char* error, size_t errorSize);
// Filtered lookup of `channels` channels from `firstChannel` at st[0], st[1] over the footprint
// axes (dsdx, dtdx, dsdy, dtdy); outside [0, 1] the image continues along s and t as wrap[0]
// and wrap[1] say (kGlintOiioWrap...); returns 0 on success.
using GlintOiioTextureLookup = int (*)(void* handle, const float* st, const float* axes,
                                       const int* wrap, int firstChannel, int channels, float* out);
enum { kGlintOiioWrapRepeat = 0, kGlintOiioWrapClamp = 1, kGlintOiioWrapMirror = 2 };
// The unfiltered texels of rows [y0, y1) of an opened texture's full-resolution level, `channels`
// floats each from channel 0, into out (width × (y1 − y0) × channels); returns 0 on success,
// else nonzero with OpenImageIO's message.
using GlintOiioTextureTexels = int (*)(void* handle, int width, int y0, int y1, int channels,
                                       float* out, char* error, size_t errorSize);
}

inline constexpr const char* kGlintOiioModuleName = "libglint_oiio.so";
inline constexpr const char* kGlintOiioWriteImageSymbol = "glint_oiio_write_image";
inline constexpr const char* kGlintOiioTextureOpenSymbol = "glint_oiio_texture_open";
inline constexpr const char* kGlintOiioTextureOpenMemorySymbol = "glint_oiio_texture_open_memory";
inline constexpr const char* kGlintOiioTextureLookupSymbol = "glint_oiio_texture_lookup";
inline constexpr const char* kGlintOiioTextureLoadSymbol = "glint_oiio_texture_load";
inline constexpr const char* kGlintOiioTextureTexelsSymbol = "glint_oiio_texture_texels";
