#pragma once
// Display images for people, made through OpenColorIO: scene-linear film → (look) → display /
// view → 8-bit PNG/JPEG or 16-bit TIFF, with straight alpha when the frame is transparent. The
// config is --ocio-config, else $OCIO, else the config bundled in the repository (ocio/config.ocio,
// compiled in), so a display image never depends on what happens to be installed.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "film/film.h"
#include "film/image_file.h"

namespace glint {

// The bundled config's name of the space Glint renders in (scene-linear Rec.709, D65), which
// every EXR it writes names in glint:colorspace.
inline constexpr const char* kRenderingColorspace = "lin_rec709";

// The bundled config's default display and view (its first display, and that display's first
// view): what the help texts state, and what a test checks the config against.
inline constexpr const char* kBundledDefaultDisplay = "sRGB";
inline constexpr const char* kBundledDefaultView = "ACES 1.0 - SDR Video";

struct DisplaySettings {
  std::string configPath;  // empty: $OCIO, else the bundled config
  std::string display;     // empty: the config's default display
  std::string view;        // empty: the display's default view
  std::string look;        // optional, applied in scene-linear before the view
  // The colour space the pixels are in: Glint renders in kRenderingColorspace; a foreign EXR
  // without glint:colorspace is taken to be in the config's scene_linear role (empty).
  std::string source = kRenderingColorspace;
  // A foreign EXR whose chromaticities name no colour space of the config: its RGB to `source`
  // (row-major 3 × 3), applied first.
  std::optional<std::array<double, 9>> toSource;
};

// One OCIO CPU processor, built once, applied to RGB rows in parallel.
class DisplayTransform {
 public:
  // Throws GlintError naming the config and the display, view or look that is wrong.
  explicit DisplayTransform(const DisplaySettings& settings);
  ~DisplayTransform();
  DisplayTransform(const DisplayTransform&) = delete;
  DisplayTransform& operator=(const DisplayTransform&) = delete;

  // In place, on width × height pixels of `channels` floats (RGB first); alpha is untouched.
  void apply(float* pixels, int width, int height, int channels) const;
  const std::string& configSource() const { return source_; }
  const std::string& display() const { return display_; }
  const std::string& view() const { return view_; }
  // The colour tag of the display (film/display_tag.h); kind None for a view whose colour space
  // is data (Raw) or a display Glint does not know (then `tagKnown` is false).
  const ColourTag& colourTag() const { return tag_; }
  bool tagKnown() const { return tagKnown_; }

 private:
  struct Impl;
  Impl* impl_;
  std::string source_, display_, view_;
  ColourTag tag_;
  bool tagKnown_ = true;
};

// Colours from a texture's colour space into Glint's rendering space (kRenderingColorspace),
// through the OCIO config ($OCIO, else the bundled one) where it knows the space, else through
// the bundled config. Thread-safe.
class ToRenderingSpace {
 public:
  // Throws UsageError naming `colorspace` when neither config knows it.
  explicit ToRenderingSpace(const std::string& colorspace);
  ~ToRenderingSpace();
  ToRenderingSpace(const ToRenderingSpace&) = delete;
  ToRenderingSpace& operator=(const ToRenderingSpace&) = delete;

  bool isIdentity() const { return identity_; }
  void apply(float* rgb) const;  // one pixel, in place

 private:
  struct Impl;
  Impl* impl_;
  bool identity_ = false;
};

// Writes `rgba` (width × height × 4, scene-linear, premultiplied) as a display image; the
// format comes from the extension (film/image_format.h): .png and .jpg/.jpeg 8-bit, .tif/.tiff
// 16-bit. A `transparent` frame gives PNG and TIFF a straight alpha channel: each pixel's colour
// is un-premultiplied in scene-linear and then developed (alpha 0: colour 0); a JPEG, which has
// no alpha, shows the frame over black. PNGs carry the display's colour tag. Throws UsageError,
// writing nothing, where the view gives values that are not finite.
void writeDisplayImage(const std::string& path, std::vector<float> rgba, int width, int height,
                       const DisplaySettings& settings, bool transparent);
void writeDisplayImage(const std::string& path, const Film& film, const DisplaySettings& settings,
                       bool transparent);

// The names of the colour spaces of the config `configPath` (as DisplaySettings::configPath).
std::vector<std::string> ocioColorSpaces(const std::string& configPath);
// Whether that config knows `name` (a colour space's name or alias).
bool ocioHasColorSpace(const std::string& configPath, const std::string& name);

// The active config's source, displays, their views, and colour spaces, for `glint info --ocio`.
std::string describeOcioConfig(const std::string& configPath);

}  // namespace glint
