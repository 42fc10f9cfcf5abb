#pragma once
// Which of an image's channels (film/exr_output.h's Image, read in Glint's channel order) are
// colour: the commands that measure or show colour need R, G and B, and refuse other images
// (depth, a luminance "Y") by name instead of treating them as colour.
#include <string>

#include "film/exr_output.h"

namespace glint {

// Throws UsageError "PATH: COMMAND needs R, G and B channels; it has ..." unless the image's
// first three channels are one layer's R, G and B ("R", or "beauty.R").
void requireRgb(const Image& image, const std::string& path, const std::string& command);

// Whether the image's fourth channel is the alpha (A) of the layer of its R, G and B.
bool hasAlpha(const Image& image);

}  // namespace glint
