#include "film/exr_output.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfCompressionAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/input_files.h"
#include "core/unwritten_allocator.h"
#include "film/atomic_file.h"
#include "film/exr_input.h"
#include "film/image_limits.h"

namespace glint {

namespace {

struct CompressionName {
  const char* name;
  Imf::Compression compression;
};
constexpr CompressionName kCompressions[] = {
    {"none", Imf::NO_COMPRESSION},   {"rle", Imf::RLE_COMPRESSION},
    {"zips", Imf::ZIPS_COMPRESSION}, {"zip", Imf::ZIP_COMPRESSION},
    {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
    {"b44", Imf::B44_COMPRESSION},   {"b44a", Imf::B44A_COMPRESSION},
    {"dwaa", Imf::DWAA_COMPRESSION}, {"dwab", Imf::DWAB_COMPRESSION}};

Imf::Compression compressionNamed(const std::string& name) {
  for (const CompressionName& c : kCompressions)
    if (name == c.name) return c.compression;
  throw UsageError("unknown EXR compression " + excerpt(name));
}

bool roundsFloats(const std::string& compression) {
  return compression == "pxr24" || compression == "dwaa" || compression == "dwab";
}

// Whether `plane` is a Cryptomatte layer of `film`: its name is one the film's
// cryptomatte/KEY/name attributes give, followed by its rank's two digits.
bool holdsIds(const Film& film, const FilmPlane& plane) {
  if (plane.isUint || plane.name.size() < 3) return false;
  const std::string layer = plane.name.substr(0, plane.name.size() - 2);
  for (const auto& [key, value] : film.stringAttributes())
    if (key.rfind("cryptomatte/", 0) == 0 && key.size() > 5 &&
        key.compare(key.size() - 5, 5, "/name") == 0 && value == layer)
      return true;
  return false;
}

}  // namespace

void checkIdsSurviveCompression(bool hasIds, const ExrOptions& options) {
  if (hasIds && !options.multipart && roundsFloats(options.compression))
    throw UsageError("compression " + options.compression +
                     " rounds floats and would destroy the Cryptomatte IDs: write the frame "
                     "multipart (its Cryptomatte parts are then compressed with zip) or with a "
                     "compression that keeps floats (zip, zips, piz, rle, b44, b44a or none)");
}

void setExrThreads(int threads) {
  if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
}

const std::vector<std::string>& exrCompressions() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const CompressionName& c : kCompressions) v.emplace_back(c.name);
    return v;
  }();
  return names;
}

namespace {

// One part of the file: its channels, each from the beauty or an AOV plane, in its own type.
struct Channel {
  std::string name;
  Imf::PixelType type;
  const float* beauty = nullptr;  // interleaved values: the film's RGBA,
  const double* plane = nullptr;  // or an AOV plane's
  size_t stride = 0, offset = 0;  // channels per pixel in the source, and this one's index
  bool clamped = false;           // whether a value is beyond the type's finite range

  double value(size_t pixel) const {
    const size_t i = pixel * stride + offset;
    return beauty ? double(beauty[i]) : plane[i];
  }
  // Whether OpenEXR reads it straight from the film: the pixels are written as they are, with
  // no copy of the frame made to pack them.
  bool direct() const { return beauty && type == Imf::FLOAT && !clamped; }
};

struct Part {
  std::string name;
  std::vector<Channel> channels;
  bool keepsFloats = false;  // it holds Cryptomatte IDs, which no compression may round
};

std::vector<Part> layoutParts(const Film& film, bool half, bool multipart) {
  const Imf::PixelType beautyType = half ? Imf::HALF : Imf::FLOAT;
  std::vector<Part> parts(1);
  parts[0].name = "rgba";
  const char* rgbaNames[] = {"R", "G", "B", "A"};
  for (size_t c = 0; c < 4; ++c)
    parts[0].channels.push_back({rgbaNames[c], beautyType, film.rgba().data(), nullptr, 4, c});
  for (const FilmPlane& plane : film.planes()) {
    // A UINT plane is Glint's own state (the resume state), not an image: it stays with the
    // beauty in part 0, where --resume reads it. In a part of its own it would hold no channel
    // a compositor reads, and Blender fails such a part and leaves the parts after it black.
    if (multipart && !plane.isUint) parts.push_back({plane.name, {}});
    Part& part = multipart && plane.isUint ? parts.front() : parts.back();
    part.keepsFloats = part.keepsFloats || holdsIds(film, plane);
    for (size_t c = 0; c < plane.channels.size(); ++c)
      part.channels.push_back({plane.channels[c], plane.isUint ? Imf::UINT : Imf::FLOAT, nullptr,
                               plane.values.data(), plane.channels.size(), c});
  }
  return parts;
}

// OpenEXR's capDate ("YYYY:MM:DD hh:mm:ss", local time) and utcOffset (UTC = local + offset).
std::pair<std::string, float> captureDate() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return {text, float(-local.tm_gmtoff)};
}

// The largest finite value of a channel type: half's is 65504, far below what a hot spot or a
// variance reaches, and a value past it would be written as +Inf.
double largestFinite(Imf::PixelType type) {
  if (type == Imf::HALF) return 65504.0;
  return static_cast<double>(std::numeric_limits<float>::max());
}

// Clamps `v` to its channel type's finite range (NaN to 0); returns whether it had to.
bool clampToType(double& v, Imf::PixelType type) {
  const double limit = largestFinite(type);
  if (std::abs(v) <= limit) return false;
  v = std::isnan(v) ? 0.0 : std::copysign(limit, v);
  return true;
}

// How many values of the parts' channels clampToType changes, marking the channels that hold
// one (counted before the headers are written, so that they can say it, without packing every
// part at once). The beauty is counted from the film's floats: for a half channel, a mean
// within float rounding above 65504 reads 65504 and is not counted (it is written as 65504
// either way).
uint64_t countClamped(std::vector<Part>& parts, size_t pixels) {
  uint64_t clamped = 0;
  for (Part& part : parts)
    for (Channel& c : part.channels) {
      if (c.type == Imf::UINT) continue;
      uint64_t inChannel = 0;
      for (size_t p = 0; p < pixels; ++p) {
        double v = c.value(p);
        inChannel += clampToType(v, c.type);
      }
      c.clamped = inChannel > 0;
      clamped += inChannel;
    }
  return clamped;
}

// The pixels of a part's channels that OpenEXR cannot read from their source (Channel::direct)
// in their native types, interleaved; values beyond a type's finite range clamped to it: an
// EXR never holds Inf or NaN. Every byte is written.
using PackedPart = std::vector<unsigned char, UnwrittenAllocator<unsigned char>>;

size_t packedBytesPerPixel(const Part& part) {
  size_t bytes = 0;
  for (const Channel& c : part.channels)
    if (!c.direct()) bytes += pixelTypeSize(c.type);
  return bytes;
}

PackedPart packPart(const Part& part, size_t pixels) {
  PackedPart out(pixels * packedBytesPerPixel(part));
  if (out.empty()) return out;  // every channel is read from the film
  unsigned char* dst = out.data();
  for (size_t p = 0; p < pixels; ++p)
    for (const Channel& c : part.channels) {
      if (c.direct()) continue;
      double v = c.value(p);
      if (c.type == Imf::UINT) {
        const auto u = static_cast<uint32_t>(v);
        std::memcpy(dst, &u, 4);
      } else {
        clampToType(v, c.type);
        if (c.type == Imf::HALF) {
          const Imath::half h(static_cast<float>(v));
          std::memcpy(dst, &h, 2);
        } else {
          const auto f = static_cast<float>(v);
          std::memcpy(dst, &f, 4);
        }
      }
      dst += pixelTypeSize(c.type);
    }
  return out;
}

}  // namespace

uint64_t writeExr(const std::string& path, const Film& film, ExrMetadata meta,
                  const ExrOptions& options) {
  const PixelWindow& w = film.window();
  checkIdsSurviveCompression(std::any_of(film.planes().begin(), film.planes().end(),
                                         [&](const FilmPlane& p) { return holdsIds(film, p); }),
                             options);
  std::vector<Part> parts = layoutParts(film, options.half, options.multipart);
  const uint64_t clamped = countClamped(parts, size_t(w.area()));
  meta.ints.push_back(
      {"glint:clamped_values", static_cast<int>(std::min<uint64_t>(clamped, INT32_MAX))});

  std::vector<Imf::Header> headers;
  for (const Part& part : parts) {
    Imf::Header h(Imath::Box2i({0, 0}, {film.fullWidth() - 1, film.fullHeight() - 1}),
                  Imath::Box2i({w.x0, w.y0}, {w.x1 - 1, w.y1 - 1}));
    h.compression() = compressionNamed(part.keepsFloats && roundsFloats(options.compression)
                                           ? std::string("zip")
                                           : options.compression);
    for (const Channel& c : part.channels) h.channels().insert(c.name, Imf::Channel(c.type));
    // OpenEXR's standard statement of the pixels' primaries and white (its default: Rec.709,
    // D65), and when the frame was made.
    Imf::addChromaticities(h, Imf::Chromaticities());
    h.pixelAspectRatio() = meta.pixelAspectRatio;
    const auto [date, utcOffset] = captureDate();
    Imf::addCapDate(h, date);
    Imf::addUtcOffset(h, utcOffset);
    if (parts.size() > 1) {
      h.setName(part.name);
      h.setType(Imf::SCANLINEIMAGE);
    }
    for (const auto& [k, v] : meta.strings) h.insert(k, Imf::StringAttribute(v));
    for (const auto& [k, v] : meta.ints) h.insert(k, Imf::IntAttribute(v));
    for (const auto& [k, v] : film.stringAttributes()) h.insert(k, Imf::StringAttribute(v));
    for (const auto& [k, v] : film.intAttributes()) h.insert(k, Imf::IntAttribute(v));
    for (const auto& [k, v] : meta.floats) h.insert(k, Imf::FloatAttribute(v));
    for (const auto& [k, m] : meta.matrices) {
      // Imath multiplies row vectors (p' = p·M): the transpose of Glint's column-vector matrix.
      Imath::M44f rowVector;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) rowVector[c][r] = m(r, c);
      h.insert(k, Imf::M44fAttribute(rowVector));
    }
    headers.push_back(std::move(h));
  }

  // The pixels of part i as OpenEXR slices of the film or of the part's packed buffer.
  const auto frameBufferOf = [&](size_t i, const PackedPart& data) {
    const size_t packedBytes = packedBytesPerPixel(parts[i]);
    Imf::FrameBuffer frameBuffer;
    size_t offset = 0;
    const auto slice = [&](const Channel& c, const void* first, size_t pixelBytes) {
      frameBuffer.insert(
          c.name, Imf::Slice::Make(c.type, first, Imath::V2i(w.x0, w.y0), w.width(), w.height(),
                                   pixelBytes, pixelBytes * size_t(w.width())));
    };
    for (const Channel& c : parts[i].channels) {
      if (c.direct()) {
        slice(c, c.beauty + c.offset, c.stride * sizeof(float));
        continue;
      }
      slice(c, data.data() + offset, packedBytes);
      offset += pixelTypeSize(c.type);
    }
    return frameBuffer;
  };
  writeFileAtomically(path, [&](const std::string& tmp) {
    writeExrStream(path, tmp, [&](Imf::OStream& stream) {
      if (parts.size() == 1) {
        Imf::OutputFile file(stream, headers[0]);
        const PackedPart data = packPart(parts[0], size_t(w.area()));
        file.setFrameBuffer(frameBufferOf(0, data));
        file.writePixels(w.height());
        return;
      }
      Imf::MultiPartOutputFile file(stream, headers.data(), int(headers.size()));
      for (size_t i = 0; i < parts.size(); ++i) {
        const PackedPart data = packPart(parts[i], size_t(w.area()));
        Imf::OutputPart out(file, int(i));
        out.setFrameBuffer(frameBufferOf(i, data));
        out.writePixels(w.height());
      }
    });
  });
  return clamped;
}

void writeExrStream(const std::string& path, const std::string& tmpPath,
                    const std::function<void(Imf::OStream&)>& write) {
  std::ofstream out(tmpPath, std::ios::binary | std::ios::trunc);
  if (!out) throw GlintError("cannot write " + path + ": cannot create the file");
  try {
    Imf::StdOFStream stream(out, tmpPath.c_str());
    write(stream);  // OpenEXR's file object is gone when this returns: every byte is handed over
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory while writing " + path);
  } catch (const std::exception& e) {
    throw GlintError("cannot write " + path + ": " + e.what());
  }
  out.close();
  if (!out) throw GlintError("cannot write " + path + ": the disk refused the data");
}

Image readImage(const std::string& path, ExrParts parts) {
  noteInputFile(path);
  // Every failure here is the file's: unreadable, truncated, not an image, or too large. It is
  // reported as a usage error (exit 2) naming the file, like a scene's mistakes.
  const auto file = openExr(path);
  const Imf::Header& header = file->header(0);
  const ExrWindow window = exrWindow(path, header);
  Image img;
  // Each part read and the index of its first channel in the image's pixels.
  std::vector<std::pair<int, size_t>> partsRead{{0, 0}};
  img.channelNames = channelsInReadingOrder(header.channels());
  if (img.channelNames.empty()) throw UsageError(path + ": the image has no channels");
  for (int part = 1; parts == ExrParts::All && part < file->parts(); ++part) {
    const Imf::Header& h = file->header(part);
    const std::string partName = h.hasName() ? h.name() : std::to_string(part);
    // Laid beside part 0 pixel for pixel, or not at all (another tool's cropped AOV part).
    if (h.dataWindow() != header.dataWindow() || h.displayWindow() != header.displayWindow()) {
      img.partsLeftOut.push_back("part " + std::to_string(part) + " (" + inQuotes(partName) +
                                 ") covers other pixels than part 0");
      continue;
    }
    partsRead.emplace_back(part, img.channelNames.size());
    // A name an earlier part already has is qualified by its part's ("diffuse.R").
    for (const std::string& name : channelsInReadingOrder(h.channels())) {
      const auto taken = [&](const std::string& n) {
        return std::find(img.channelNames.begin(), img.channelNames.end(), n) !=
               img.channelNames.end();
      };
      const std::string unique = taken(name) ? partName + "." + name : name;
      if (taken(unique))
        throw UsageError(path + ": part " + std::to_string(part) + " (" + inQuotes(partName) +
                         ") has channel " + inQuotes(name) + ", which an earlier part has as " +
                         inQuotes(unique) + " too");
      img.channelNames.push_back(unique);
    }
  }
  img.channels = int(img.channelNames.size());
  checkImageFits(path, "data window", window.width, window.height, 4.0 * img.channels);
  img.width = window.width;
  img.height = window.height;
  img.x = window.x;
  img.y = window.y;
  img.fullWidth = window.fullWidth;
  img.fullHeight = window.fullHeight;
  if (const auto* cs = header.findTypedAttribute<Imf::StringAttribute>("glint:colorspace"))
    img.colorspace = cs->value();
  if (Imf::hasChromaticities(header)) {
    const Imf::Chromaticities& c = Imf::chromaticities(header);
    img.chromaticities = {c.red.x,  c.red.y,  c.green.x, c.green.y,
                          c.blue.x, c.blue.y, c.white.x, c.white.y};
  }
  const size_t pixelBytes = sizeof(float) * size_t(img.channels);
  for (size_t k = 0; k < partsRead.size(); ++k) {
    const auto [part, first] = partsRead[k];
    const size_t end = k + 1 < partsRead.size() ? partsRead[k + 1].second : img.channelNames.size();
    // The file's own names (the image's may be qualified), at the image's offsets.
    const std::vector<std::string> names = channelsInReadingOrder(file->header(part).channels());
    std::vector<ExrSlice> slices;
    for (size_t c = first; c < end; ++c)
      slices.push_back({names[c - first], Imf::FLOAT, c * sizeof(float)});
    if (part == 0) {
      readPixelsInBands(path, *file, 0, slices, pixelBytes, img.pixels);
      continue;
    }
    // Into the pixels part 0 laid out, band by band.
    size_t at = 0;
    readPixelsInBands(path, *file, part, slices, pixelBytes, [&](size_t bytes) {
      char* band = reinterpret_cast<char*>(img.pixels.data()) + at;
      at += bytes;
      return band;
    });
  }
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
