#include "io/texture_formats.h"

#include <string_view>

#include "core/error.h"
#include "core/file_names.h"

namespace glint {

namespace {

struct TextureFormat {
  std::string_view extension, reader;
};

constexpr TextureFormat kTextureFormats[] = {
    {".png", "png"},     {".jpg", "jpeg"},    {".jpeg", "jpeg"}, {".jpe", "jpeg"},
    {".jfif", "jpeg"},   {".hdr", "hdr"},     {".rgbe", "hdr"},  {".exr", "openexr"},
    {".sxr", "openexr"}, {".mxr", "openexr"}, {".tif", "tiff"},  {".tiff", "tiff"},
    {".tx", "tiff"},     {".psd", "psd"},     {".pdd", "psd"},   {".psb", "psd"},
    {".tga", "targa"},   {".tpic", "targa"},  {".bmp", "bmp"},   {".dib", "bmp"},
    {".pnm", "pnm"},     {".ppm", "pnm"},     {".pgm", "pnm"},   {".pbm", "pnm"},
    {".pfm", "pnm"},
};

}  // namespace

std::string textureReaderFormat(const std::string& name) {
  const std::string extension = lowerExtension(name);
  for (const TextureFormat& f : kTextureFormats)
    if (f.extension == extension) return std::string(f.reader);
  throw GlintError(
      "cannot read texture " + name + ": " +
      (extension.empty()
           ? std::string("its name has no extension")
           : "\"" + extension + "\" is not an image format Glint reads textures from") +
      "; Glint reads PNG, JPEG, Radiance HDR (.hdr), OpenEXR (.exr), TIFF (.tif, .tiff, .tx), "
      "Photoshop (.psd), Targa (.tga), BMP (.bmp) and PNM (.ppm, .pgm, .pfm) files, by their "
      "extension (oiiotool converts the others: oiiotool IN -o OUT.exr)");
}

}  // namespace glint
