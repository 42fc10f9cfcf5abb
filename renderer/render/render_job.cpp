#include "render/render_job.h"

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

void checkSampleSets(const Scene& scene, int64_t spp) {
  const std::string limit = "the sampler's limit of " + std::to_string(kMaxSampleSet);
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

void checkFrameFits(int64_t pixels, size_t channels, uint64_t availableBytes) {
  const double needed = double(pixels) * (12.0 * double(channels) + 16.0);
  if (availableBytes == 0 || needed <= double(availableBytes)) return;
  throw UsageError("a frame of " + std::to_string(pixels) + " pixels with " +
                   std::to_string(channels) + " channels needs about " + gigabytes(needed) +
                   " of memory (film in double, float copies to write it); " +
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
