#pragma once
// The image formats a texture may be read from, by the file's extension. PNG, JPEG and Radiance
// HDR are read by Glint's own readers (io/own_texture_readers.h); what those leave, and OpenEXR,
// TIFF, Photoshop, Targa, BMP and PNM/PFM files, by OpenImageIO's reader of that format alone
// (film/oiio_module.h). OpenImageIO 2.4 reads two dozen formats more, and some of its readers
// fail badly on a hostile file of a few hundred bytes (IFF corrupts the heap, DPX asserts, SGI
// allocates gigabytes, Zfile reads a truncated file as black, ffmpeg opens the files a script
// names and may wait for ever): a texture never reaches those, whatever its bytes.
#include <string>

namespace glint {

// OpenImageIO's name of the reader for the texture `name` (a path, or an embedded image's
// name), from its extension; GlintError naming `name` and the formats read where there is none.
std::string textureReaderFormat(const std::string& name);

}  // namespace glint
