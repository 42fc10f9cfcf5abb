#pragma once
// The one image-comparison routine: error metrics between a test image and a reference, used by
// `glint compare`, `glint converge` and the tests. RGB channels only (alpha is coverage).
#include <string>

#include "film/exr_output.h"

namespace glint {

struct ImageErrors {
  double rmse = 0;    // √(mean over pixels and channels of (a − b)²)
  double relmse = 0;  // mean of (a − b)² / (b² + ε), ε = 1e-2 (pbrt's relative MSE)
  double mae = 0;     // mean |a − b|
  double maxAbs = 0;  // max |a − b|
  double psnr = 0;    // 10·log10(1 / MSE), peak 1 (display white); +∞ for identical images
  double aboveThreshold = 0;  // share of pixels whose largest channel error exceeds the threshold
  size_t pixels = 0;
  size_t nonfinitePixels = 0;  // pixels with a NaN or infinite R, G or B in either image
  // Where both images lie in frames of other sizes, a note the caller gives as a warning: they
  // were compared pixel for pixel, which may not set the same pixels side by side.
  std::string placement;
};

inline constexpr double kRelMseEpsilon = 1e-2;
// The per-pixel error share_above_threshold counts by default.
inline constexpr double kDefaultCompareThreshold = 1e-2;

// What the errors of compareImages name the two images by: their paths, where they have them.
struct ComparedNames {
  std::string test = "the image", reference = "the reference";
};

// Throws UsageError, naming both images, when the sizes differ, or when both images lie in
// frames of one size (an array lies in none) at other places. Non-finite values count as an
// error of +∞.
ImageErrors compareImages(const Image& test, const Image& reference,
                          double threshold = kDefaultCompareThreshold,
                          const ComparedNames& names = {});

// The warning for errors with non-finite pixels (nonfinitePixels > 0), which make the figures
// infinite or NaN (null in JSON, where identical images' +∞ PSNR is null too).
std::string nonfiniteNote(const ImageErrors& errors, const ComparedNames& names);

// Throws UsageError, naming `path`, the pixel and the channel, where a reference's R, G or B is
// not finite: every error measured against it would be +∞ or NaN (converge's log-log axes).
void requireFiniteReference(const Image& reference, const std::string& path);

// A false-colour image of the per-pixel error (largest channel |a − b|), on a logarithmic ramp
// from 1e-4 (black) through blue, green, yellow to 1 and above (white); PNG.
void writeDifferenceImage(const std::string& path, const Image& test, const Image& reference,
                          const ComparedNames& names = {});

}  // namespace glint
