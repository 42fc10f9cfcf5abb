#pragma once
// The colour space of an EXR that `glint convert` develops: the one named on the command line,
// else Glint's own glint:colorspace, else what OpenEXR's standard chromaticities attribute
// says, else the OCIO config's scene_linear role. Chromaticities that match a colour space of
// the bundled config name it; others are converted exactly, by the matrix they define.
#include <array>
#include <optional>
#include <string>

#include "film/display.h"
#include "film/exr_output.h"

namespace glint {

struct InputColorspace {
  std::string source;  // for DisplaySettings::source; empty: the config's scene_linear role
  std::optional<std::array<double, 9>> toSource;  // for DisplaySettings::toSource
  std::string why;                                // for the log: how it was chosen
};

// `named` is --input-colorspace (empty: not given), already checked against the config.
// Throws UsageError naming `path` when its chromaticities cannot describe an RGB space
// (non-finite, or primaries on one line).
InputColorspace inputColorspace(const Image& image, const std::string& path,
                                const std::string& named);

// Row-major linear RGB → CIE XYZ of the primaries and white (x, y) in `rgbw` (red, green, blue,
// white), scaled so that white has Y = 1; nullopt when they span no RGB space.
std::optional<std::array<double, 9>> rgbToXyz(const std::array<double, 8>& rgbw);

}  // namespace glint
