#include "film/merge.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "core/input_files.h"
#include "film/atomic_file.h"

namespace glint {

namespace {

struct Crop {
  std::string path;
  OIIO::ImageSpec spec;
  std::vector<unsigned char> pixels;  // every channel, in its native type
};

Crop readCrop(const std::string& path) {
  noteInputFile(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw GlintError("cannot read " + path + ": " + OIIO::geterror());
  Crop c{path, in->spec(), {}};
  if (in->seek_subimage(1, 0))
    throw UsageError(path +
                     " has several parts: merge takes single-part crops (render them "
                     "without --multipart)");
  in->seek_subimage(0, 0);
  c.pixels.resize(c.spec.image_bytes(/*native=*/true));
  if (!in->read_image(0, 0, 0, c.spec.nchannels, OIIO::TypeDesc::UNKNOWN, c.pixels.data()))
    throw GlintError("cannot read " + path + ": " + in->geterror());
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

  std::vector<int> owner(size_t(W) * size_t(H), -1);
  const size_t pixelBytes = first.spec.pixel_bytes(/*native=*/true);
  std::vector<unsigned char> frame(size_t(W) * size_t(H) * pixelBytes, 0);
  for (size_t k = 0; k < crops.size(); ++k) {
    const OIIO::ImageSpec& s = crops[k].spec;
    if (s.x < 0 || s.y < 0 || s.x + s.width > W || s.y + s.height > H)
      throw UsageError(crops[k].path + ": data window lies outside the frame");
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const int fx = s.x + x, fy = s.y + y;
        const size_t at = size_t(fy) * size_t(W) + size_t(fx);
        if (owner[at] >= 0)
          throw UsageError(crops[k].path + " and " + crops[size_t(owner[at])].path +
                           " overlap at pixel (" + std::to_string(fx) + ", " + std::to_string(fy) +
                           ")");
        owner[at] = int(k);
        std::memcpy(&frame[at * pixelBytes],
                    &crops[k].pixels[(size_t(y) * size_t(s.width) + size_t(x)) * pixelBytes],
                    pixelBytes);
      }
  }
  std::vector<bool> covered(owner.size());
  for (size_t i = 0; i < owner.size(); ++i) covered[i] = owner[i] >= 0;
  const std::vector<PixelWindow> holes = missingRegions(covered, W, H);
  if (!holes.empty()) {
    std::string msg = "the crops leave " + std::to_string(holes.size()) +
                      " region(s) of the frame unrendered; render them with:";
    for (const PixelWindow& h : holes) msg += "\n  " + window(h);
    throw UsageError(msg);
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
