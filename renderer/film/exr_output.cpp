#include "film/exr_output.h"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/input_files.h"
#include "film/atomic_file.h"
#include "film/banded_read.h"
#include "film/exr_input.h"
#include "film/image_limits.h"

namespace glint {

const std::vector<std::string>& exrCompressions() {
  static const std::vector<std::string> names = {"none",  "rle", "zips", "zip",  "piz",
                                                 "pxr24", "b44", "b44a", "dwaa", "dwab"};
  return names;
}

namespace {

// One part of the file: its channels, each from the beauty or an AOV plane, in its own type.
struct Channel {
  std::string name;
  OIIO::TypeDesc type;
  const std::vector<double>* source;  // interleaved values
  size_t stride, offset;              // channels per pixel in `source`, and this one's index
};

struct Part {
  std::string name;
  std::vector<Channel> channels;
};

std::vector<Part> layoutParts(const Film& film, const std::vector<double>& rgba, bool half,
                              bool multipart) {
  const OIIO::TypeDesc beautyType = half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
  std::vector<Part> parts(1);
  parts[0].name = "rgba";
  const char* rgbaNames[] = {"R", "G", "B", "A"};
  for (size_t c = 0; c < 4; ++c)
    parts[0].channels.push_back({rgbaNames[c], beautyType, &rgba, 4, c});
  for (const FilmPlane& plane : film.planes()) {
    if (multipart) parts.push_back({plane.name, {}});
    for (size_t c = 0; c < plane.channels.size(); ++c)
      parts.back().channels.push_back({plane.channels[c],
                                       plane.isUint ? OIIO::TypeDesc::UINT : OIIO::TypeDesc::FLOAT,
                                       &plane.values, plane.channels.size(), c});
  }
  return parts;
}

// The largest finite value of a channel type: half's is 65504, far below what a hot spot or a
// variance reaches, and a value past it would be written as +Inf.
double largestFinite(OIIO::TypeDesc type) {
  if (type == OIIO::TypeDesc::HALF) return 65504.0;
  return static_cast<double>(std::numeric_limits<float>::max());
}

// Clamps `v` to its channel type's finite range (NaN to 0); returns whether it had to.
bool clampToType(double& v, OIIO::TypeDesc type) {
  const double limit = largestFinite(type);
  if (std::abs(v) <= limit) return false;
  v = std::isnan(v) ? 0.0 : std::copysign(limit, v);
  return true;
}

// How many values of the parts' channels clampToType changes (counted before the headers are
// written, so that they can say it, without packing every part at once).
uint64_t countClamped(const std::vector<Part>& parts, size_t pixels) {
  uint64_t clamped = 0;
  for (const Part& part : parts)
    for (const Channel& c : part.channels) {
      if (c.type == OIIO::TypeDesc::UINT) continue;
      for (size_t p = 0; p < pixels; ++p) {
        double v = (*c.source)[p * c.stride + c.offset];
        clamped += clampToType(v, c.type);
      }
    }
  return clamped;
}

// The pixels of a part in its native per-channel types, interleaved; values beyond a type's
// finite range clamped to it: an EXR never holds Inf or NaN.
std::vector<unsigned char> packPart(const Part& part, size_t pixels) {
  size_t bytesPerPixel = 0;
  for (const Channel& c : part.channels) bytesPerPixel += c.type.size();
  std::vector<unsigned char> out(pixels * bytesPerPixel);
  unsigned char* dst = out.data();
  for (size_t p = 0; p < pixels; ++p)
    for (const Channel& c : part.channels) {
      double v = (*c.source)[p * c.stride + c.offset];
      if (c.type == OIIO::TypeDesc::UINT) {
        const auto u = static_cast<uint32_t>(v);
        std::memcpy(dst, &u, 4);
      } else {
        clampToType(v, c.type);
        if (c.type == OIIO::TypeDesc::HALF) {
          const Imath::half h(static_cast<float>(v));
          std::memcpy(dst, &h, 2);
        } else {
          const auto f = static_cast<float>(v);
          std::memcpy(dst, &f, 4);
        }
      }
      dst += c.type.size();
    }
  return out;
}

}  // namespace

uint64_t writeExr(const std::string& path, const Film& film, ExrMetadata meta,
                  const ExrOptions& options) {
  const PixelWindow& w = film.window();
  std::vector<double> rgba(static_cast<size_t>(w.area()) * 4);
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x)
      std::copy_n(film.pixel(x, y), 4,
                  &rgba[(size_t(y - w.y0) * size_t(w.width()) + size_t(x - w.x0)) * 4]);
  const std::vector<Part> parts = layoutParts(film, rgba, options.half, options.multipart);
  const uint64_t clamped = countClamped(parts, size_t(w.area()));
  meta.ints.push_back(
      {"glint:clamped_values", static_cast<int>(std::min<uint64_t>(clamped, INT32_MAX))});

  std::vector<OIIO::ImageSpec> specs;
  for (const Part& part : parts) {
    OIIO::ImageSpec spec(w.width(), w.height(), int(part.channels.size()), part.channels[0].type);
    spec.channelnames.clear();
    spec.channelformats.clear();
    for (const Channel& c : part.channels) {
      spec.channelnames.push_back(c.name);
      spec.channelformats.push_back(c.type);
    }
    spec.alpha_channel = part.name == "rgba" ? 3 : -1;
    spec.x = w.x0;
    spec.y = w.y0;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = film.fullWidth();
    spec.full_height = film.fullHeight();
    spec.attribute("compression", options.compression);
    // OpenEXR's standard statement of the pixels' primaries and white: Rec.709, D65.
    static const float kRec709Chromaticities[8] = {0.64f, 0.33f, 0.30f,   0.60f,
                                                   0.15f, 0.06f, 0.3127f, 0.3290f};
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8),
                   kRec709Chromaticities);
    if (parts.size() > 1) spec.attribute("name", part.name);
    for (const auto& [k, v] : meta.strings) spec.attribute(k, v);
    for (const auto& [k, v] : meta.ints) spec.attribute(k, v);
    for (const auto& [k, v] : film.stringAttributes()) spec.attribute(k, v);
    for (const auto& [k, v] : film.intAttributes()) spec.attribute(k, v);
    for (const auto& [k, v] : meta.floats) spec.attribute(k, v);
    for (const auto& [k, m] : meta.matrices) {
      float rowVector[16];
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) rowVector[4 * c + r] = m(r, c);
      spec.attribute(k, OIIO::TypeMatrix44, rowVector);
    }
    specs.push_back(std::move(spec));
  }

  writeFileAtomically(path, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) throw GlintError("OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
    if (!out->open(tmp, int(specs.size()), specs.data()))
      throw GlintError("cannot write " + path + ": " + out->geterror());
    for (size_t i = 0; i < parts.size(); ++i) {
      if (i > 0 && !out->open(tmp, specs[i], OIIO::ImageOutput::AppendSubimage))
        throw GlintError("cannot write " + path + ": " + out->geterror());
      const std::vector<unsigned char> data = packPart(parts[i], size_t(w.area()));
      if (!out->write_image(OIIO::TypeDesc::UNKNOWN, data.data()))
        throw GlintError("cannot write " + path + ": " + out->geterror());
    }
    if (!out->close()) throw GlintError("cannot write " + path + ": " + out->geterror());
  });
  return clamped;
}

Image readImage(const std::string& path) {
  noteInputFile(path);
  // Every failure here is the file's: unreadable, truncated, not an image, or too large. It is
  // reported as a usage error (exit 2) naming the file, like a scene's mistakes.
  const auto in = openExr(path);
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels <= 0) throw UsageError(path + ": the image has no channels");
  checkImageFits(path, "data window", spec.width, spec.height, 4.0 * spec.nchannels);
  Image img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.channelNames = spec.channelnames;
  img.x = spec.x;
  img.y = spec.y;
  img.fullWidth = spec.full_width;
  img.fullHeight = spec.full_height;
  img.colorspace = spec.get_string_attribute("glint:colorspace");
  if (!readPixelsInBands(*in, spec, OIIO::TypeDesc::FLOAT, size_t(img.channels), img.pixels))
    throw UsageError("cannot read " + path + ": " + excerpt(in->geterror()));
  return img;
}

Image imageFromFilm(const Film& film) {
  const PixelWindow& w = film.window();
  Image img;
  img.width = w.width();
  img.height = w.height();
  img.channels = 4;
  img.x = w.x0;
  img.y = w.y0;
  img.fullWidth = film.fullWidth();
  img.fullHeight = film.fullHeight();
  img.pixels = film.toFloatRgba();
  return img;
}

}  // namespace glint
