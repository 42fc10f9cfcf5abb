#pragma once
// Radiance HDR (RGBE) textures read by Glint itself, as PNGs are by libpng (io/png_texture.h),
// so that a scene lit by an HDR sky never loads OpenImageIO's module (film/oiio_module.h),
// whose load costs more than a small scene's render (docs/performance.md, "Start-up and
// memory"). It reads as OpenImageIO 2.4's HDR reader reads (its header lines in 128-byte
// pieces, its run-length decoding, a flat scanline wherever one does not start with the
// run-length marker, its table of exponents) and gives the same header, oiio:ColorSpace and
// floats (tests/io/hdr_texture_test.cpp compares them bit for bit) and the same refusals.
#include <cstddef>
#include <string>

#include "film/oiio_module.h"
#include "film/oiio_module_abi.h"

namespace glint::hdr_texture {

// Opens the file `path` as a texture when Glint reads it itself, and fills `info` as
// OpenImageIO's reader does. Glint reads a name ending in .hdr or .rgbe (the reader OpenImageIO
// picks for it) whose first line starts with "#?", whose header sets no GAMMA (from which
// OpenImageIO names a colour space) and whose size line is the usual "-Y height +X width" (the
// other orientations OpenImageIO reads without turning them). Returns the handle; null with a
// message in `error` for an HDR file that cannot be read; null with `*declined` set for a file
// OpenImageIO must read.
void* open(const std::string& path, GlintOiioTextureInfo* info, char* error, size_t errorSize,
           bool* declined);

// The same for an image file's bytes held in memory (they must outlive the handle); `name`
// ends in the format's extension, as for OpenImageIO.
void* openMemory(const std::string& name, const void* bytes, size_t size,
                 GlintOiioTextureInfo* info, char* error, size_t errorSize, bool* declined);

// The reader and closer of what open() and openMemory() return, with the module's contracts
// (rows read in order, film/oiio_module_abi.h); `open` and `openMemory` are left null.
const oiio_module::TextureFunctions& functions();

}  // namespace glint::hdr_texture
