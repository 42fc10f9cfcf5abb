#include "film/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "core/error.h"
#include "film/image_file.h"

namespace glint {

namespace {

// Throws unless the images can be set pixel for pixel; returns a note where they can but may
// not be the same pixels: both lie in frames (an array does not), of other sizes.
std::string checkSameShape(const Image& a, const Image& b, const ComparedNames& names) {
  const auto size = [](const Image& i) {
    return std::to_string(i.width) + "x" + std::to_string(i.height);
  };
  if (a.width != b.width || a.height != b.height)
    throw UsageError("images differ in size: " + names.test + " is " + size(a) + ", " +
                     names.reference + " " + size(b));
  for (const auto& [image, name] : {std::pair{&a, &names.test}, std::pair{&b, &names.reference}})
    if (image->channels < 3)
      throw UsageError(*name + " has " + std::to_string(image->channels) +
                       " channels: images are compared by R, G and B");
  const auto known = [](const Image& i) { return i.fullWidth > 0 && i.fullHeight > 0; };
  if (!known(a) || !known(b)) return "";
  const auto place = [](const Image& i) {
    return "(" + std::to_string(i.x) + ", " + std::to_string(i.y) + ") of a " +
           std::to_string(i.fullWidth) + "x" + std::to_string(i.fullHeight) + " frame";
  };
  const std::string where =
      size(a) + ": " + names.test + " at " + place(a) + ", " + names.reference + " at " + place(b);
  // Two crops of one frame that lie apart are other pixels of the scene.
  if (a.fullWidth == b.fullWidth && a.fullHeight == b.fullHeight) {
    if (a.x != b.x || a.y != b.y) throw UsageError("images cover other pixels: " + where);
    return "";
  }
  // In frames of other sizes they may be (a reference cut out by another tool) or not.
  return "the images lie in frames of other sizes, " + where + ": compared pixel for pixel";
}

double channel(const Image& img, size_t pixel, int c) {
  return img.pixels[pixel * size_t(img.channels) + size_t(c)];
}

double pixelError(const Image& a, const Image& b, size_t p) {
  double e = 0;
  for (int c = 0; c < 3; ++c) {
    const double d = std::fabs(channel(a, p, c) - channel(b, p, c));
    e = std::max(e, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
  }
  return e;
}

}  // namespace

void requireFiniteReference(const Image& reference, const std::string& path) {
  if (reference.channels < 3) return;  // not RGB: compareImages refuses it
  const size_t pixels = size_t(reference.width) * size_t(reference.height);
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c)
      if (const double v = channel(reference, p, c); !std::isfinite(v))
        throw UsageError(path + ": channel " +
                         (reference.channelNames.size() > size_t(c)
                              ? reference.channelNames[size_t(c)]
                              : std::string(1, "RGB"[c])) +
                         " is " + (std::isnan(v) ? "NaN" : "infinite") + " at pixel (" +
                         std::to_string(reference.x + int(p % size_t(reference.width))) + ", " +
                         std::to_string(reference.y + int(p / size_t(reference.width))) +
                         "): errors against it would not be finite");
}

ImageErrors compareImages(const Image& a, const Image& b, double threshold,
                          const ComparedNames& names) {
  ImageErrors e;
  e.placement = checkSameShape(a, b, names);
  e.pixels = size_t(a.width) * size_t(a.height);
  double se = 0, rel = 0, ae = 0;
  size_t above = 0;
  for (size_t p = 0; p < e.pixels; ++p) {
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      const double ref = channel(b, p, c);
      const double d = channel(a, p, c) - ref;
      finite = finite && std::isfinite(channel(a, p, c)) && std::isfinite(ref);
      const double ad = std::isfinite(d) ? std::fabs(d) : std::numeric_limits<double>::infinity();
      se += ad * ad;
      // Not ∞/∞ (NaN) where the reference is the infinite one: every measure of a non-finite
      // pixel is infinite, whichever image holds it.
      rel += std::isfinite(d) ? ad * ad / (ref * ref + kRelMseEpsilon) : ad;
      ae += ad;
      e.maxAbs = std::max(e.maxAbs, ad);
    }
    above += pixelError(a, b, p) > threshold;
    e.nonfinitePixels += !finite;
  }
  const double n = double(e.pixels) * 3;
  const double mse = se / n;
  e.rmse = std::sqrt(mse);
  e.relmse = rel / n;
  e.mae = ae / n;
  e.psnr = mse > 0 ? 10 * std::log10(1 / mse) : std::numeric_limits<double>::infinity();
  e.aboveThreshold = double(above) / double(e.pixels);
  return e;
}

std::string nonfiniteNote(const ImageErrors& e, const ComparedNames& names) {
  return names.test + " against " + names.reference + ": " + std::to_string(e.nonfinitePixels) +
         " of " + std::to_string(e.pixels) +
         " pixels hold a NaN or infinite R, G or B, whose errors count as infinite";
}

void writeDifferenceImage(const std::string& path, const Image& a, const Image& b,
                          const ComparedNames& names) {
  checkSameShape(a, b, names);
  // Stops of the ramp at log10(error) = −4, −3, −2, −1, 0.
  static const float kRamp[5][3] = {
      {0, 0, 0}, {0.1f, 0.2f, 0.9f}, {0.1f, 0.8f, 0.3f}, {1, 0.85f, 0.1f}, {1, 1, 1}};
  std::vector<uint16_t> rgb(size_t(a.width) * size_t(a.height) * 3);
  for (size_t p = 0; p < size_t(a.width) * size_t(a.height); ++p) {
    const double err = pixelError(a, b, p);
    const double s = std::clamp(std::log10(std::max(err, 1e-4)) + 4, 0.0, 4.0);
    const int i = std::min(3, static_cast<int>(s));
    const double f = s - i;
    for (int c = 0; c < 3; ++c)
      rgb[p * 3 + size_t(c)] =
          static_cast<uint16_t>(std::lround(255 * ((1 - f) * kRamp[i][c] + f * kRamp[i + 1][c])));
  }
  writeRgbImage(path, a.width, a.height, 8, rgb);
}

}  // namespace glint
