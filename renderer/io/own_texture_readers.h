#pragma once
// The texture readers Glint has of its own: PNG by libpng (io/png_texture.h), JPEG by libjpeg
// (io/jpeg_texture.h), Radiance HDR by Glint (io/hdr_texture.h). Each gives what OpenImageIO
// 2.4's reader of its format gives (the header, oiio:ColorSpace, the floats bit for bit) and
// declines what is not its format or what only OpenImageIO decides. io/texture_file.cpp tries
// them in turn before OpenImageIO's module; the readers' tests and the texture fuzzer take them
// from here.
#include <cstddef>
#include <string>

#include "film/oiio_module.h"
#include "film/oiio_module_abi.h"
#include "io/hdr_texture.h"
#include "io/jpeg_texture.h"
#include "io/png_texture.h"

namespace glint {

struct OwnTextureReader {
  const char* library;  // what decodes the format, for messages
  const char* name;     // a file name the reader takes (its format's extension)
  void* (*open)(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
                bool* declined);
  void* (*openMemory)(const std::string& name, const void* bytes, size_t size,
                      GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined);
  const oiio_module::TextureFunctions& (*functions)();
};

inline constexpr OwnTextureReader kPngReader{"libpng", "texture.png", png_texture::open,
                                             png_texture::openMemory, png_texture::functions};
inline constexpr OwnTextureReader kJpegReader{"libjpeg", "texture.jpg", jpeg_texture::open,
                                              jpeg_texture::openMemory, jpeg_texture::functions};
inline constexpr OwnTextureReader kHdrReader{"Glint", "texture.hdr", hdr_texture::open,
                                             hdr_texture::openMemory, hdr_texture::functions};
inline constexpr const OwnTextureReader* kOwnTextureReaders[] = {&kPngReader, &kJpegReader,
                                                                 &kHdrReader};

}  // namespace glint
