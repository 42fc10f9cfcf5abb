#pragma once
// The film: scene-linear RGBA for the pixels of a crop window of the full frame, in float, the
// precision of the files it goes to (the pixels' states behind it are double), so that an EXR
// is written straight from it. Each pixel is written by exactly one tile task, so no
// synchronisation is needed.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/unwritten_allocator.h"

namespace glint {

// Pixel bounds [x0, x1) × [y0, y1) inside a full frame of width × height.
struct PixelWindow {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  int64_t area() const { return int64_t(width()) * height(); }
};

// An extra image plane (AOV): named channels per pixel, float or uint32 in the file.
struct FilmPlane {
  std::string name;                   // e.g. "normal"; the part name in multi-part EXRs
  std::vector<std::string> channels;  // e.g. {"N.X", "N.Y", "N.Z"}
  bool isUint = false;         // written as UINT (the resume state, kept in part 0), else FLOAT
  std::vector<double> values;  // window area × channels
};

// Whether a new film's RGBA starts at zero, or unwritten: for a film whose every pixel its maker
// writes, or whose RGBA nothing reads, so that no thread zeroes what is written again later.
enum class FilmPixels { Zeroed, Unwritten };

class Film {
 public:
  Film(int fullWidth, int fullHeight, const PixelWindow& window,
       FilmPixels pixels = FilmPixels::Zeroed);

  int fullWidth() const { return fullWidth_; }
  int fullHeight() const { return fullHeight_; }
  const PixelWindow& window() const { return window_; }

  // (x, y) in full-frame pixel coordinates, inside window(). Each value is rounded to float;
  // one beyond float's finite range becomes an infinity, so that whoever writes the film to a
  // file sees that it has to be clamped.
  void setPixel(int x, int y, double r, double g, double b, double a);
  const float* pixel(int x, int y) const;  // 4 values: R, G, B, A
  // The window's pixels row by row, 4 values each.
  std::span<const float> rgba() const { return rgba_; }

  // Row-major float RGBA of the window, for image output.
  std::vector<float> toFloatRgba() const;

  // AOV planes, added before rendering; each pixel is written by the task that owns it.
  size_t addPlane(std::string name, std::vector<std::string> channels, bool isUint = false);
  void setPlanePixel(size_t plane, int x, int y, const double* values);
  double* planePixel(size_t plane, int x, int y);  // the plane's channels at (x, y)
  const double* planePixel(size_t plane, int x, int y) const;
  const std::vector<FilmPlane>& planes() const { return planes_; }

  // Metadata that belongs with the planes, for whoever reads them (Cryptomatte's names and
  // manifests): written into the file's header. A key given again replaces its value.
  void addAttribute(const std::string& key, std::string value);
  void addAttribute(const std::string& key, int value);
  const std::vector<std::pair<std::string, std::string>>& stringAttributes() const {
    return stringAttributes_;
  }
  const std::vector<std::pair<std::string, int>>& intAttributes() const { return intAttributes_; }

 private:
  size_t offset(int x, int y) const;
  int fullWidth_, fullHeight_;
  PixelWindow window_;
  std::vector<float, UnwrittenAllocator<float>> rgba_;
  std::vector<FilmPlane> planes_;
  std::vector<std::pair<std::string, std::string>> stringAttributes_;
  std::vector<std::pair<std::string, int>> intAttributes_;
};

}  // namespace glint
