#pragma once
// What an image output's extension names. The format always follows the extension, and an
// output refuses an extension it cannot write before any work is done, so no file is ever one
// format under another's name. Every command that writes images asks here.
#include <string>

namespace glint {

enum class ImageFormat { Exr, Png, Jpeg, Tiff, Svg };

// What an output may hold: the scene-linear frame (EXR), a display-referred image made through
// the OCIO view (PNG, JPEG, TIFF), either, or a plot (SVG).
enum class ImageOutput { Exr, Display, ExrOrDisplay, Plot };

// The format `path`'s extension names, checked against what `output` accepts. Throws
// UsageError naming `option` (e.g. "-o"), the path and the extensions accepted.
ImageFormat imageOutputFormat(const std::string& option, const std::string& path,
                              ImageOutput output);

// PNG, JPEG and TIFF: display-referred, 8 or 16 bits per channel.
inline bool isDisplayFormat(ImageFormat f) {
  return f == ImageFormat::Png || f == ImageFormat::Jpeg || f == ImageFormat::Tiff;
}

// Whether the format can store an alpha channel (JPEG cannot).
inline bool hasAlphaChannel(ImageFormat f) { return f != ImageFormat::Jpeg; }

// "PNG", "JPEG", ...: for messages.
const char* formatName(ImageFormat f);

}  // namespace glint
