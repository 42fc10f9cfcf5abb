#pragma once
// PNG textures read by libpng itself, so that a scene whose textures are PNGs never loads
// OpenImageIO's module (film/oiio_module.h), whose load costs more than a small asset's render
// (docs/performance.md, "Start-up and memory"). It makes the libpng calls OpenImageIO 2.4's PNG
// reader makes, and gives the same header, oiio:ColorSpace and floats
// (tests/io/png_texture_test.cpp compares them bit for bit), so io/texture_file.cpp reads it
// through the module's own interface.
#include <cstddef>
#include <string>

#include "film/oiio_module.h"
#include "film/oiio_module_abi.h"

namespace glint::png_texture {

// Opens the file `path` as a texture when Glint reads it itself, and fills `info` as
// OpenImageIO's reader does. Glint reads a name ending in .png (the reader OpenImageIO picks
// for it) whose bytes start with the PNG signature and carry no Exif or XMP (whose colour space
// only OpenImageIO's decoders of those decide). Returns the handle; null with a message in `error`
// for a PNG that cannot be read; null with `*declined` set for a file OpenImageIO must read.
void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined);

// The same for an image file's bytes held in memory (they must outlive the handle); `name`
// ends in the format's extension, as for OpenImageIO.
void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined);

// The reader and closer of what open() and openMemory() return, with the module's contracts
// (rows read in order, film/oiio_module_abi.h); `open` and `openMemory` are left null.
const oiio_module::TextureFunctions& functions();

}  // namespace glint::png_texture
