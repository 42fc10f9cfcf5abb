#pragma once
// JPEG textures read by libjpeg itself, as PNG textures are by libpng (io/png_texture.h), so that
// a scene whose textures are JPEGs never loads OpenImageIO's module (film/oiio_module.h), whose
// load costs more than a small asset's render (docs/performance.md, "Start-up and memory"). It
// makes the libjpeg calls OpenImageIO 2.4's JPEG reader makes, with the same library, and gives
// the same header, oiio:ColorSpace and floats (tests/io/jpeg_texture_test.cpp compares them bit
// for bit) and the same refusals: libjpeg's errors, and its warnings, which OpenImageIO reports
// as errors. Beyond OpenImageIO, it bounds what a hostile file can make it do: the coefficient
// buffer of a multi-scan file is checked against the memory budget before it is allocated, and a
// file of more than kMaxScans scans is refused (each scan passes over the whole image).
#include <cstddef>
#include <string>

#include "film/oiio_module.h"
#include "film/oiio_module_abi.h"

namespace glint::jpeg_texture {

// More scans than any encoder writes (a progressive JPEG has about ten; libjpeg-turbo's own
// fuzzers stop at 500): past it, a file is refused rather than decoded scan after scan.
inline constexpr int kMaxScans = 1000;

// Opens the file `path` as a texture when Glint reads it itself, and fills `info` as
// OpenImageIO's reader does. Glint reads a name ending in a JPEG extension (.jpg, .jpeg, .jpe,
// .jif, .jfif, .jfi: the reader OpenImageIO picks for it) whose bytes start with the JPEG
// marker, carry no XMP (whose properties OpenImageIO keeps under their own names,
// oiio:ColorSpace among them) and are not CMYK (which OpenImageIO converts itself). Returns the
// handle; null with a message in `error` for a JPEG that cannot be read; null with `*declined`
// set for a file OpenImageIO must read.
void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined);

// The same for an image file's bytes held in memory (they must outlive the handle); `name`
// ends in the format's extension, as for OpenImageIO.
void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined);

// The reader and closer of what open() and openMemory() return, with the module's contracts
// (rows read in order, film/oiio_module_abi.h); `open` and `openMemory` are left null.
const oiio_module::TextureFunctions& functions();

}  // namespace glint::jpeg_texture
