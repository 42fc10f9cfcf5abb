#pragma once
// Image textures read from files into a MIP pyramid in memory (materials/mip_pyramid.h): PNGs
// by libpng (io/png_texture.h), JPEGs by libjpeg (io/jpeg_texture.h), Radiance HDRs by Glint
// (io/hdr_texture.h), the rest by OpenImageIO (through its module, film/oiio_module.h: only
// scenes with such textures load it), filtered over each lookup's footprint; colours converted
// to the rendering space by OCIO.
// Texture input is the scene's input, so it lives in io/: it gives materials/ and lights/ what
// they sample and reaches down to film/ for the image module and the colour conversion that
// output shares.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lights/environment.h"
#include "materials/image_texture.h"

namespace glint {

// The largest texture file read. The pixels an image may take are bounded apart
// (film/image_limits.h); this bound is on the file, so that no file of any size is taken on
// trust: a 16k x 16k RGBA float texture with its mip levels, uncompressed, is 5.4 GB.
inline constexpr uint64_t kMaxTextureFileBytes = uint64_t{8} << 30;

// The colour space a file's texels are taken to be in when the scene does not say:
// half or float texels (EXR, HDR) are scene-linear already; integer texels (PNG, JPEG, 8- and
// 16-bit TIFF) are the sRGB encoding ("sRGB - Texture"), unless the file declares itself linear.
std::string defaultTextureColorspace(bool floatTexels, const std::string& declared);

// Opens `path` (a PNG, a JPEG, a Radiance HDR, or an image file OpenImageIO reads) as a texture in
// `colorspace` (empty: as above). Its texels are read whole now, so a truncated or corrupt file is
// refused here. Throws GlintError naming the file when it cannot be read or holds more pixels than
// an image read may take (film/image_limits.h), OutOfMemoryError when its pyramid (4/3 of its
// texels, in float) does not fit the memory budget, and UsageError for a colour space OCIO does not
// know.
std::shared_ptr<const ImageTexture> openImageTexture(const std::string& path,
                                                     const std::string& colorspace = "");

// The same for an image file's bytes held in memory (a glTF file's embedded PNG or JPEG):
// `name` says where it came from in messages and ends in the format's extension (".png").
std::shared_ptr<const ImageTexture> openImageTextureInMemory(const std::string& name,
                                                             const std::string& bytes);

// The texels of an opened texture's full-resolution image, unfiltered, converted to the
// rendering space as color() converts them (grey to all three channels), row 0 at the top: what
// an environment light samples. Checks first that width × height × bytesPerTexel fit the memory
// budget (core/memory.h); throws GlintError naming a texture not read from an image file.
LatLongImage readTexels(const ImageTexture& texture, double bytesPerTexel);

}  // namespace glint
