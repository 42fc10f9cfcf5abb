#include "film/image_format.h"

#include <optional>

#include "core/error.h"
#include "core/file_names.h"

namespace glint {

namespace {

std::optional<ImageFormat> formatOfExtension(const std::string& ext) {
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  if (ext == ".svg") return ImageFormat::Svg;
  return std::nullopt;
}

bool accepts(ImageOutput output, ImageFormat f) {
  switch (output) {
    case ImageOutput::Exr:
      return f == ImageFormat::Exr;
    case ImageOutput::Display:
      return isDisplayFormat(f);
    case ImageOutput::ExrOrDisplay:
      return f == ImageFormat::Exr || isDisplayFormat(f);
    case ImageOutput::Plot:
      return f == ImageFormat::Svg;
  }
  return false;
}

constexpr const char* kDisplayExtensions = ".png, .jpg, .jpeg, .tif or .tiff";

std::string accepted(ImageOutput output) {
  switch (output) {
    case ImageOutput::Exr:
      return ".exr (the scene-linear frame)";
    case ImageOutput::Display:
      return std::string(kDisplayExtensions) + " (a display-referred image, through the OCIO view)";
    case ImageOutput::ExrOrDisplay:
      return ".exr (the scene-linear frame), or " + std::string(kDisplayExtensions) +
             " (a display-referred image, through the OCIO view)";
    case ImageOutput::Plot:
      return ".svg";
  }
  return {};
}

}  // namespace

ImageFormat imageOutputFormat(const std::string& option, const std::string& path,
                              ImageOutput output) {
  const std::string ext = lowerExtension(path);
  const std::optional<ImageFormat> format = formatOfExtension(ext);
  if (format && accepts(output, *format)) return *format;
  const std::string what = ext.empty() ? "has no extension"
                           : format    ? "names the " + std::string(formatName(*format)) + " format"
                                       : "has an extension Glint does not write";
  throw UsageError(option + " " + excerpt(path) + ": " + what + "; " + option + " writes " +
                   accepted(output));
}

const char* formatName(ImageFormat f) {
  switch (f) {
    case ImageFormat::Exr:
      return "OpenEXR";
    case ImageFormat::Png:
      return "PNG";
    case ImageFormat::Jpeg:
      return "JPEG";
    case ImageFormat::Tiff:
      return "TIFF";
    case ImageFormat::Svg:
      return "SVG";
  }
  return "?";
}

}  // namespace glint
