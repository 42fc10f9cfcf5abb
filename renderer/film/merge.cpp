#include "film/merge.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/input_files.h"
#include "core/log.h"
#include "film/atomic_file.h"
#include "film/exr_input.h"
#include "film/exr_output.h"
#include "film/image_limits.h"

namespace glint {

namespace {

struct Crop {
  CropRecord record;  // its path too
  const std::string& path() const { return record.path; }
  Imf::Header header;
  ExrWindow window;
  std::vector<ExrSlice> slices;  // every channel in its native type, in the file's order
  size_t pixelBytes = 0;
  std::vector<unsigned char> pixels;
};

// Glint writes no Inf or NaN (a value beyond its channel's type is clamped to it): a crop that
// holds one was not written by Glint as rendered, and merging would copy it into the frame.
void refuseNonFinite(const Crop& c) {
  const size_t pixels = size_t(c.window.width) * size_t(c.window.height);
  for (size_t p = 0; p < pixels; ++p)
    for (const ExrSlice& s : c.slices) {
      if (s.type == Imf::UINT) continue;
      const unsigned char* at = &c.pixels[p * c.pixelBytes + s.offset];
      float v;
      if (s.type == Imf::HALF) {
        Imath::half h;
        std::memcpy(&h, at, sizeof h);
        v = float(h);
      } else {
        std::memcpy(&v, at, sizeof v);
      }
      if (std::isfinite(v)) continue;
      const int x = c.window.x + int(p % size_t(c.window.width)),
                y = c.window.y + int(p / size_t(c.window.width));
      throw UsageError(c.path() + ": channel " + excerpt(s.name) + " is " +
                       (std::isnan(v) ? "NaN" : "infinite") + " at pixel (" + std::to_string(x) +
                       ", " + std::to_string(y) +
                       "); Glint never writes one, so the crop was changed after it was "
                       "rendered: render it again");
    }
}

// Like readImage, every failure is the file's (exit 2, naming it), and the declared data window
// is checked against memory before its pixels are allocated.
Crop readCrop(const CropRecord& record) {
  const std::string& path = record.path;
  noteInputFile(path);
  const auto file = openExr(path);
  if (file->parts() > 1)
    throw UsageError(path +
                     " has several parts: merge takes single-part crops (render them "
                     "without --multipart)");
  Crop c{record, file->header(0), exrWindow(path, file->header(0)), {}, 0, {}};
  const Imf::ChannelList& channels = c.header.channels();
  for (auto ch = channels.begin(); ch != channels.end(); ++ch) {
    c.slices.push_back({ch.name(), ch.channel().type, c.pixelBytes});
    c.pixelBytes += pixelTypeSize(ch.channel().type);
  }
  if (c.slices.empty()) throw UsageError(path + ": the image has no channels");
  checkImageFits(path, "data window", c.window.width, c.window.height, double(c.pixelBytes));
  readPixelsInBands(path, *file, 0, c.slices, c.pixelBytes, c.pixels);
  refuseNonFinite(c);
  return c;
}

// Names and types, in the file's order: crops are copied byte for byte into the first's layout,
// and OpenEXR's ChannelList equality compares the types alone (alpha renamed "Y" would have
// been copied into B).
bool sameChannels(const Crop& a, const Crop& b) {
  return std::equal(
      a.slices.begin(), a.slices.end(), b.slices.begin(), b.slices.end(),
      [](const ExrSlice& x, const ExrSlice& y) { return x.name == y.name && x.type == y.type; });
}

std::string channelNames(const Crop& c) {
  std::string names;
  for (const ExrSlice& s : c.slices) names += (names.empty() ? "" : ", ") + inQuotes(s.name);
  return names;
}

// A copy of `h` without the attributes named in `leftOut`. (Header::erase of OpenEXR 3.1 leaks
// the attribute it removes, and a crop may give an attribute Glint sets another type, which
// insert refuses to change: so the merged header is built without them instead.)
Imf::Header headerWithout(const Imf::Header& h, const std::vector<std::string>& leftOut) {
  Imf::Header copy;
  for (auto a = h.begin(); a != h.end(); ++a)
    if (std::find(leftOut.begin(), leftOut.end(), a.name()) == leftOut.end())
      copy.insert(a.name(), a.attribute());
  return copy;
}

// The frame's estimated RMSE and relMSE from its crops': each is a mean over pixels (the RMSE's
// square), so the frame's is the crops' weighted by their pixels; and its fewest and most
// samples of a pixel. An estimate some crop lacks is left out.
void addMergedEstimates(const std::vector<Crop>& crops, Imf::Header& header) {
  double pixels = 0, mse = 0, relmse = 0;
  bool rmseKnown = true, relmseKnown = true, sppKnown = true;
  int minSpp = std::numeric_limits<int>::max(), maxSpp = 0;
  for (const Crop& c : crops) {
    const CropRecord& r = c.record;
    const double n = double(c.window.width) * double(c.window.height);
    pixels += n;
    rmseKnown = rmseKnown && r.estimatedRmse;
    relmseKnown = relmseKnown && r.estimatedRelmse;
    sppKnown = sppKnown && r.minPixelSpp && r.maxPixelSpp;
    if (rmseKnown) mse += n * double(*r.estimatedRmse) * double(*r.estimatedRmse);
    if (relmseKnown) relmse += n * double(*r.estimatedRelmse);
    if (sppKnown) {
      minSpp = std::min(minSpp, *r.minPixelSpp);
      maxSpp = std::max(maxSpp, *r.maxPixelSpp);
    }
  }
  if (rmseKnown)
    header.insert("glint:estimated_rmse", Imf::FloatAttribute(float(std::sqrt(mse / pixels))));
  if (relmseKnown)
    header.insert("glint:estimated_relmse", Imf::FloatAttribute(float(relmse / pixels)));
  if (sppKnown) {
    header.insert("glint:min_pixel_spp", Imf::IntAttribute(minSpp));
    header.insert("glint:max_pixel_spp", Imf::IntAttribute(maxSpp));
  }
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

MergeReport mergeCrops(const std::string& outPath, const std::vector<CropRecord>& records,
                       const std::string& commandLine, const std::string& expectedSceneHash) {
  if (records.empty()) throw UsageError("merge needs at least one crop");
  std::vector<Crop> crops;
  for (const CropRecord& r : records) crops.push_back(readCrop(r));
  const Crop& first = crops[0];
  const auto settingsHash = [](const Crop& c) { return c.record.settingsHash; };
  const std::string hash = settingsHash(first);
  if (hash.empty())
    throw UsageError(first.path() + ": not a Glint render (no glint:settings_hash)");
  const int W = first.window.fullWidth, H = first.window.fullHeight;
  for (const Crop& c : crops) {
    if (settingsHash(c) != hash)
      throw UsageError(c.path() + " comes from a different scene or settings than " + first.path() +
                       " (glint:settings_hash " + settingsHash(c) + " vs " + hash + ")");
    if (c.window.fullWidth != W || c.window.fullHeight != H)
      throw UsageError(c.path() + ": frame " + std::to_string(c.window.fullWidth) + "x" +
                       std::to_string(c.window.fullHeight) + " differs from " + first.path());
    if (!sameChannels(c, first))
      throw UsageError(c.path() + " has other channels or pixel types than " + first.path() + " (" +
                       channelNames(c) + " against " + channelNames(first) + ")");
    const std::string& sceneHash = c.record.sceneHash;
    if (!expectedSceneHash.empty() && sceneHash != expectedSceneHash)
      throw UsageError(c.path() + " was rendered from another scene file (glint:scene_hash " +
                       sceneHash + ", expected " + expectedSceneHash +
                       "): the scene changed after the job was planned");
    if (c.record.partial)
      throw UsageError(c.path() + " is a partial (interrupted) render: render its crop again");
  }

  // Placement is decided on the crops' rectangles: the display window is allocated only once the
  // crops are known to tile it, so it is never larger than the pixels already read. A 375-byte
  // crop declaring a 60000 x 60000 frame once made merge allocate 57 GB (an owner index, the
  // pixel and a coverage bit for each pixel of the frame) before finding the holes.
  for (const Crop& c : crops) {
    const ExrWindow& s = c.window;
    // In 64 bits: a data window near INT_MAX overflowed int here.
    if (s.x < 0 || s.y < 0 || int64_t{s.x} + s.width > W || int64_t{s.y} + s.height > H)
      throw UsageError(c.path() + ": data window lies outside the frame");
  }
  const auto windowOf = [](const ExrWindow& s) {
    return PixelWindow{s.x, s.x + s.width, s.y, s.y + s.height};
  };
  int64_t covered = 0;
  for (size_t k = 0; k < crops.size(); ++k) {
    const PixelWindow a = windowOf(crops[k].window);
    covered += int64_t{a.width()} * a.height();
    // The first pixel of crop k, in row order, that an earlier crop holds.
    std::optional<std::pair<std::pair<int, int>, size_t>> clash;  // ((y, x), earlier crop)
    for (size_t j = 0; j < k; ++j) {
      const PixelWindow b = windowOf(crops[j].window);
      const int x0 = std::max(a.x0, b.x0), y0 = std::max(a.y0, b.y0);
      if (x0 >= std::min(a.x1, b.x1) || y0 >= std::min(a.y1, b.y1)) continue;
      if (!clash || std::pair{y0, x0} < clash->first) clash = {{y0, x0}, j};
    }
    if (clash)
      throw UsageError(crops[k].path() + " and " + crops[clash->second].path() +
                       " overlap at pixel (" + std::to_string(clash->first.second) + ", " +
                       std::to_string(clash->first.first) + ")");
  }
  if (covered != int64_t{W} * H) {
    std::vector<PixelWindow> windows;
    for (const Crop& c : crops) windows.push_back(windowOf(c.window));
    const std::vector<PixelWindow> holes = missingRegions(windows, W, H);
    std::string msg = "the crops leave " + std::to_string(holes.size()) + " region(s) of the " +
                      std::to_string(W) + "x" + std::to_string(H) + " frame of " + first.path() +
                      " unrendered; render them with:";
    for (const PixelWindow& h : holes) msg += "\n  " + window(h);
    throw UsageError(msg);
  }
  const size_t pixelBytes = first.pixelBytes;
  checkImageFits(first.path(), "display window", W, H, double(pixelBytes));
  std::vector<unsigned char> frame(size_t(W) * size_t(H) * pixelBytes, 0);
  for (const Crop& c : crops) {
    const ExrWindow& s = c.window;
    const size_t rowBytes = size_t(s.width) * pixelBytes;
    for (int y = 0; y < s.height; ++y)
      std::memcpy(&frame[(size_t(s.y + y) * size_t(W) + size_t(s.x)) * pixelBytes],
                  &c.pixels[size_t(y) * rowBytes], rowBytes);
  }

  // The merged frame keeps the first crop's metadata (scene, settings, hashes) over the full
  // data window; time, rays and clamped values become the sums over the crops, the estimated
  // errors and pixel spp the frame's (mergedEstimates). Each crop's passes counted its own
  // pixels and seconds, which make no frame's: they are left out.
  // A scanline frame: a tiled crop's layout and a part's chunk count do not carry over.
  // Each crop's resume state (render/resume_state.h: its glint_resume channels, where its
  // passes stood and a checksum over them) is its own: copied, the merged frame's checksum was
  // the first crop's and --resume called the frame altered. The state is left out, and said to be.
  Imf::Header header = headerWithout(first.header, {"tiles",
                                                    "chunkCount",
                                                    "type",
                                                    "name",
                                                    "glint:clamped_values",
                                                    "glint:render_seconds",
                                                    "glint:rays",
                                                    "glint:crop",
                                                    "glint:merged_crops",
                                                    "glint:commandline",
                                                    "glint:estimated_rmse",
                                                    "glint:estimated_relmse",
                                                    "glint:min_pixel_spp",
                                                    "glint:max_pixel_spp",
                                                    "glint:passes",
                                                    "glint:resume_hash",
                                                    "glint:resume_sampling",
                                                    "glint:resume_finished_end",
                                                    "glint:resume_cut_end",
                                                    "glint:resume_checksum"});
  const auto isResumeState = [](const ExrSlice& s) {
    return s.name.rfind("glint_resume.", 0) == 0;
  };
  std::vector<ExrSlice> written;
  header.channels() = Imf::ChannelList();
  for (const ExrSlice& s : first.slices)
    if (!isResumeState(s)) {
      written.push_back(s);
      header.channels().insert(s.name, Imf::Channel(s.type));
    }
  if (written.size() < first.slices.size())
    log::warning("the crops' resume states are left out of " + outPath +
                 ": a merged frame is not resumed (continue the crops with --resume, then merge "
                 "them again)");
  addMergedEstimates(crops, header);
  header.dataWindow() = Imath::Box2i({0, 0}, {W - 1, H - 1});
  header.lineOrder() = Imf::INCREASING_Y;
  float seconds = 0, rays = 0;
  int64_t clamped = 0;
  for (const Crop& c : crops) {
    seconds += c.record.renderSeconds;
    rays += c.record.rays;
    clamped += c.record.clampedValues;
  }
  header.insert("glint:clamped_values",
                Imf::IntAttribute(int(std::min<int64_t>(clamped, INT32_MAX))));
  header.insert("glint:render_seconds", Imf::FloatAttribute(seconds));
  header.insert("glint:rays", Imf::FloatAttribute(rays));
  header.insert("glint:crop",
                Imf::StringAttribute("0 " + std::to_string(W) + " 0 " + std::to_string(H)));
  header.insert("glint:merged_crops", Imf::IntAttribute(int(crops.size())));
  header.insert("glint:commandline", Imf::StringAttribute(commandLine));
  writeFileAtomically(outPath, [&](const std::string& tmp) {
    writeExrStream(outPath, tmp, [&](Imf::OStream& stream) {
      Imf::OutputFile out(stream, header);
      Imf::FrameBuffer frameBuffer;
      for (const ExrSlice& s : written)
        frameBuffer.insert(s.name,
                           Imf::Slice::Make(s.type, frame.data() + s.offset, Imath::V2i(0, 0), W, H,
                                            pixelBytes, pixelBytes * size_t(W)));
      out.setFrameBuffer(frameBuffer);
      out.writePixels(H);
    });
  });
  return {W, H, crops.size()};
}

}  // namespace glint
