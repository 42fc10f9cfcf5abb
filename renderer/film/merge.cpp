#include "film/merge.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/input_files.h"
#include "film/atomic_file.h"
#include "film/banded_read.h"
#include "film/exr_input.h"
#include "film/image_limits.h"

namespace glint {

namespace {

struct Crop {
  std::string path;
  OIIO::ImageSpec spec;
  std::vector<unsigned char> pixels;  // every channel, in its native type
};

// Like readImage, every failure is the file's (exit 2, naming it), and the declared data window
// is checked against memory before its pixels are allocated.
Crop readCrop(const std::string& path) {
  noteInputFile(path);
  const auto in = openExr(path);
  Crop c{path, in->spec(), {}};
  if (in->seek_subimage(1, 0))
    throw UsageError(path +
                     " has several parts: merge takes single-part crops (render them "
                     "without --multipart)");
  in->seek_subimage(0, 0);
  if (c.spec.nchannels <= 0) throw UsageError(path + ": the image has no channels");
  checkImageFits(path, "data window", c.spec.width, c.spec.height,
                 double(c.spec.pixel_bytes(/*native=*/true)));
  if (!readPixelsInBands(*in, c.spec, OIIO::TypeDesc::UNKNOWN, c.spec.pixel_bytes(true), c.pixels))
    throw UsageError("cannot read " + path + ": " + excerpt(in->geterror()));
  return c;
}

std::string window(const PixelWindow& w) {
  return "--crop " + std::to_string(w.x0) + " " + std::to_string(w.x1) + " " +
         std::to_string(w.y0) + " " + std::to_string(w.y1);
}

}  // namespace

std::vector<PixelWindow> missingRegions(const std::vector<bool>& coveredIn, int width, int height) {
  std::vector<bool> covered = coveredIn;
  std::vector<PixelWindow> out;
  const auto at = [&](int x, int y) { return covered[size_t(y) * size_t(width) + size_t(x)]; };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (at(x, y)) continue;
      int x1 = x;
      while (x1 < width && !at(x1, y)) ++x1;
      int y1 = y + 1;
      const auto rowMissing = [&](int row) {
        for (int i = x; i < x1; ++i)
          if (at(i, row)) return false;
        return true;
      };
      while (y1 < height && rowMissing(y1)) ++y1;
      for (int j = y; j < y1; ++j)
        for (int i = x; i < x1; ++i) covered[size_t(j) * size_t(width) + size_t(i)] = true;
      out.push_back({x, x1, y, y1});
    }
  return out;
}

std::vector<PixelWindow> missingRegions(const std::vector<PixelWindow>& crops, int width,
                                        int height) {
  // Coverage changes only at the crops' edges, so the greedy search runs on the grid of cells
  // those edges cut (at most (2n + 1)² cells, whatever the frame's size) and gives the same
  // rectangles as on pixels: each starts at a cell's corner and stops at cell edges.
  std::vector<int> xs{0, width}, ys{0, height};
  for (const PixelWindow& c : crops) {
    xs.insert(xs.end(), {c.x0, c.x1});
    ys.insert(ys.end(), {c.y0, c.y1});
  }
  for (std::vector<int>* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  const int cols = int(xs.size()) - 1, rows = int(ys.size()) - 1;
  const auto index = [](const std::vector<int>& v, int at) {
    return int(std::lower_bound(v.begin(), v.end(), at) - v.begin());
  };
  std::vector<bool> cells(size_t(cols) * size_t(rows), false);
  for (const PixelWindow& c : crops)
    for (int j = index(ys, c.y0); j < index(ys, c.y1); ++j)
      for (int i = index(xs, c.x0); i < index(xs, c.x1); ++i)
        cells[size_t(j) * size_t(cols) + size_t(i)] = true;
  std::vector<PixelWindow> out;
  for (const PixelWindow& r : missingRegions(cells, cols, rows))
    out.push_back({xs[size_t(r.x0)], xs[size_t(r.x1)], ys[size_t(r.y0)], ys[size_t(r.y1)]});
  return out;
}

MergeReport mergeCrops(const std::string& outPath, const std::vector<std::string>& cropPaths,
                       const std::string& commandLine, const std::string& expectedSceneHash) {
  if (cropPaths.empty()) throw UsageError("merge needs at least one crop");
  std::vector<Crop> crops;
  for (const auto& p : cropPaths) crops.push_back(readCrop(p));
  const Crop& first = crops[0];
  const auto settingsHash = [](const Crop& c) {
    return std::string(c.spec.get_string_attribute("glint:settings_hash"));
  };
  const std::string hash = settingsHash(first);
  if (hash.empty()) throw UsageError(first.path + ": not a Glint render (no glint:settings_hash)");
  const int W = first.spec.full_width, H = first.spec.full_height;
  for (const Crop& c : crops) {
    if (settingsHash(c) != hash)
      throw UsageError(c.path + " comes from a different scene or settings than " + first.path +
                       " (glint:settings_hash " + settingsHash(c) + " vs " + hash + ")");
    if (c.spec.full_width != W || c.spec.full_height != H)
      throw UsageError(c.path + ": frame " + std::to_string(c.spec.full_width) + "x" +
                       std::to_string(c.spec.full_height) + " differs from " + first.path);
    if (c.spec.channelnames != first.spec.channelnames ||
        c.spec.channelformats != first.spec.channelformats || c.spec.format != first.spec.format)
      throw UsageError(c.path + " has other channels or pixel types than " + first.path);
    const std::string sceneHash = c.spec.get_string_attribute("glint:scene_hash");
    if (!expectedSceneHash.empty() && sceneHash != expectedSceneHash)
      throw UsageError(c.path + " was rendered from another scene file (glint:scene_hash " +
                       sceneHash + ", expected " + expectedSceneHash +
                       "): the scene changed after the job was planned");
    if (c.spec.get_int_attribute("glint:partial", 0) != 0)
      throw UsageError(c.path + " is a partial (interrupted) render: render its crop again");
  }

  // Placement is decided on the crops' rectangles: the display window is allocated only once the
  // crops are known to tile it, so it is never larger than the pixels already read. A 375-byte
  // crop declaring a 60000 x 60000 frame once made merge allocate 57 GB (an owner index, the
  // pixel and a coverage bit for each pixel of the frame) before finding the holes.
  for (const Crop& c : crops) {
    const OIIO::ImageSpec& s = c.spec;
    // In 64 bits: a data window near INT_MAX overflowed int here.
    if (s.x < 0 || s.y < 0 || int64_t{s.x} + s.width > W || int64_t{s.y} + s.height > H)
      throw UsageError(c.path + ": data window lies outside the frame");
  }
  const auto windowOf = [](const OIIO::ImageSpec& s) {
    return PixelWindow{s.x, s.x + s.width, s.y, s.y + s.height};
  };
  int64_t covered = 0;
  for (size_t k = 0; k < crops.size(); ++k) {
    const PixelWindow a = windowOf(crops[k].spec);
    covered += int64_t{a.width()} * a.height();
    // The first pixel of crop k, in row order, that an earlier crop holds.
    std::optional<std::pair<std::pair<int, int>, size_t>> clash;  // ((y, x), earlier crop)
    for (size_t j = 0; j < k; ++j) {
      const PixelWindow b = windowOf(crops[j].spec);
      const int x0 = std::max(a.x0, b.x0), y0 = std::max(a.y0, b.y0);
      if (x0 >= std::min(a.x1, b.x1) || y0 >= std::min(a.y1, b.y1)) continue;
      if (!clash || std::pair{y0, x0} < clash->first) clash = {{y0, x0}, j};
    }
    if (clash)
      throw UsageError(crops[k].path + " and " + crops[clash->second].path + " overlap at pixel (" +
                       std::to_string(clash->first.second) + ", " +
                       std::to_string(clash->first.first) + ")");
  }
  if (covered != int64_t{W} * H) {
    std::vector<PixelWindow> windows;
    for (const Crop& c : crops) windows.push_back(windowOf(c.spec));
    const std::vector<PixelWindow> holes = missingRegions(windows, W, H);
    std::string msg = "the crops leave " + std::to_string(holes.size()) + " region(s) of the " +
                      std::to_string(W) + "x" + std::to_string(H) + " frame of " + first.path +
                      " unrendered; render them with:";
    for (const PixelWindow& h : holes) msg += "\n  " + window(h);
    throw UsageError(msg);
  }
  const size_t pixelBytes = first.spec.pixel_bytes(/*native=*/true);
  checkImageFits(first.path, "display window", W, H, double(pixelBytes));
  std::vector<unsigned char> frame(size_t(W) * size_t(H) * pixelBytes, 0);
  for (const Crop& c : crops) {
    const OIIO::ImageSpec& s = c.spec;
    const size_t rowBytes = size_t(s.width) * pixelBytes;
    for (int y = 0; y < s.height; ++y)
      std::memcpy(&frame[(size_t(s.y + y) * size_t(W) + size_t(s.x)) * pixelBytes],
                  &c.pixels[size_t(y) * rowBytes], rowBytes);
  }

  // The merged frame keeps the first crop's metadata (scene, settings, hashes) over the full
  // data window; time, rays and clamped values become the sums over the crops.
  OIIO::ImageSpec spec = first.spec;
  spec.x = spec.y = 0;
  spec.width = W;
  spec.height = H;
  float seconds = 0, rays = 0;
  int64_t clamped = 0;
  for (const Crop& c : crops) {
    seconds += c.spec.get_float_attribute("glint:render_seconds", 0);
    rays += c.spec.get_float_attribute("glint:rays", 0);
    clamped += c.spec.get_int_attribute("glint:clamped_values", 0);
  }
  spec.attribute("glint:clamped_values", int(std::min<int64_t>(clamped, INT32_MAX)));
  spec.attribute("glint:render_seconds", seconds);
  spec.attribute("glint:rays", rays);
  spec.attribute("glint:crop", "0 " + std::to_string(W) + " 0 " + std::to_string(H));
  spec.attribute("glint:merged_crops", int(crops.size()));
  spec.attribute("glint:commandline", commandLine);
  writeFileAtomically(outPath, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out || !out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UNKNOWN, frame.data()) ||
        !out->close())
      throw GlintError("cannot write " + outPath + ": " +
                       (out ? out->geterror() : OIIO::geterror()));
  });
  return {W, H, crops.size()};
}

}  // namespace glint
