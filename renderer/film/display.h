#pragma once
// Display images for people, made through OpenColorIO: scene-linear film → (look) → display /
// view → 8-bit PNG/JPEG or 16-bit TIFF. The config is --ocio-config, else $OCIO, else the config
// bundled in the repository (ocio/config.ocio, compiled in), so a display image never depends
// on what happens to be installed.
#include <string>
#include <vector>

#include "film/film.h"

namespace glint {

// The bundled config's name of the space Glint renders in (scene-linear Rec.709, D65), which
// every EXR it writes names in glint:colorspace.
inline constexpr const char* kRenderingColorspace = "lin_rec709";

struct DisplaySettings {
  std::string configPath;  // empty: $OCIO, else the bundled config
  std::string display;     // empty: the config's default display
  std::string view;        // empty: the display's default view
  std::string look;        // optional, applied in scene-linear before the view
  // The colour space the pixels are in: Glint renders in kRenderingColorspace; a foreign EXR
  // without glint:colorspace is taken to be in the config's scene_linear role (empty).
  std::string source = kRenderingColorspace;
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

 private:
  struct Impl;
  Impl* impl_;
  std::string source_;
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

// Throws UsageError unless `path` ends in .png, .jpg/.jpeg or .tif/.tiff.
void checkDisplayImagePath(const std::string& path);

// Writes `rgba` (width × height × 4, scene-linear) as a display image; the format comes from the
// extension: .png and .jpg/.jpeg 8-bit, .tif/.tiff 16-bit.
void writeDisplayImage(const std::string& path, std::vector<float> rgba, int width, int height,
                       const DisplaySettings& settings);
void writeDisplayImage(const std::string& path, const Film& film, const DisplaySettings& settings);

// The active config's source, displays, their views, and colour spaces, for `glint info --ocio`.
std::string describeOcioConfig(const std::string& configPath);

}  // namespace glint
