#include "render/render_job.h"

#include <bit>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/memory.h"
#include "core/sampler.h"
#include "render/render_session.h"

namespace glint {

bool parseIntegratorKind(const std::string& name, IntegratorKind& out) {
  if (name == "production")
    out = IntegratorKind::Production;
  else if (name == "reference")
    out = IntegratorKind::Reference;
  else
    return false;
  return true;
}

void CameraSampling::chunkRays(const SampleKey* keys, int count, Ray* out, Points& p) const {
  const Sampler& sampler = *keys[0].sampler;
  // The lens and time dimensions only where there is a lens, or motion under an open shutter.
  const bool drawLens = camera_.hasLens(), drawTime = openShutter_;
  const uint32_t dims[Points::kDims] = {dimension(Dim::Pixel), dimension(Dim::Lens),
                                        dimension(Dim::Time)};
  const bool drawn[Points::kDims] = {true, drawLens, drawTime};
  // Half 0's points (or the whole sets') before half 1's: at odd spp the halves' sets differ
  // in size, and a block of lanes draws from sets of one size. Half 1's samples are set aside
  // in one pass over the keys rather than found in a second.
  int m = 0, sets = 0, later = 0;
  int half1[kCameraChunk];
  float pixelX[kCameraChunk], pixelY[kCameraChunk];
  const SampleKey* before = nullptr;
  const auto place = [&](int i) {
    const SampleKey& key = keys[i];
    if (!before || before->px != key.px || before->py != key.py || before->half != key.half) {
      for (int d = 0; d < Points::kDims; ++d)
        if (drawn[d]) p.sets[d][size_t(sets)] = key.pattern(dims[d]);
      ++sets;
    }
    before = &key;
    for (int d = 0; d < Points::kDims; ++d)
      if (drawn[d]) p.at[d][m] = &p.sets[d][size_t(sets - 1)];
    p.flat[m] = static_cast<uint32_t>(key.index);
    pixelX[m] = static_cast<float>(key.px);
    pixelY[m] = static_cast<float>(key.py);
    p.sample[m++] = i;
  };
  for (int i = 0; i < count; ++i) {
    if (keys[i].half == 1)
      half1[later++] = i;
    else
      place(i);
  }
  for (int k = 0; k < later; ++k) place(half1[k]);
  for (int d = 0; d < Points::kDims; ++d)
    if (drawn[d]) sampler.get2DAt(p.at[d], 1, p.flat, count, p.points[d].data());
  // Film positions over the pixel offsets: nothing reads the offsets again.
  Vec2f* const film = p.points[0].data();
  for (int j = 0; j < count; ++j) film[j] = {pixelX[j] + film[j].x, pixelY[j] + film[j].y};
  camera_.generateRays(film, drawLens ? p.points[1].data() : nullptr, count, out, p.sample);
  if (drawTime)
    for (int j = 0; j < count; ++j)
      out[p.sample[j]].time = open_ + (close_ - open_) * p.points[2][size_t(j)].x;
  else if (std::bit_cast<uint32_t>(open_) != 0)
    // generateRays's rays leave at time +0, where nearly every shutter opens.
    for (int i = 0; i < count; ++i) out[i].time = open_;
}

void checkSampleSets(const Scene& scene, int64_t spp) {
  const std::string limit = "the sampler's limit of " + std::to_string(kMaxSampleSet);
  if (spp < 1)
    throw UsageError("spp " + std::to_string(spp) + " is not a sample count (at least 1)");
  if (spp > kMaxSampleSet)
    throw UsageError("spp " + std::to_string(spp) + " is more than " + limit);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const int64_t samples = lightSampleCount(scene.lights[i]);
    if (spp * samples <= kMaxSampleSet) continue;
    throw UsageError(
        "spp " + std::to_string(spp) + " × the " + std::to_string(samples) + " samples of lights[" +
        std::to_string(i) + "] = " + std::to_string(spp * samples) +
        " light samples per pixel, more than " + limit + ": lower spp or the light's \"samples\"");
  }
}

void checkFrameFits(int64_t pixels, size_t bytesPerPixel, uint64_t availableBytes,
                    const std::string& parts) {
  const double needed = double(pixels) * double(bytesPerPixel);
  if (availableBytes == 0 || needed <= double(availableBytes)) return;
  throw UsageError("a frame of " + std::to_string(pixels) + " pixels needs about " +
                   gigabytes(needed) + " of memory (" + std::to_string(bytesPerPixel) +
                   " bytes a pixel" + (parts.empty() ? "" : ": " + parts) + "); " +
                   gigabytes(double(availableBytes)) +
                   " is available: render it in pieces with --crop, or on a farm");
}

RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt,
                         const PassCallback& onPass) {
  RenderSession session(scene, accel, opt);
  session.runToEnd(onPass);
  return session.finish();
}

}  // namespace glint
