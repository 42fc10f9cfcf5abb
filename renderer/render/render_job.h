#pragma once
// Renders a scene into a film: camera samples per pixel through the integrator, box filter,
// non-finite samples counted and dropped, tiles on all cores, progress on stderr.
#include <optional>

#include "accel/accelerator.h"
#include "film/film.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

struct RenderOptions {
  int threads = 0;  // 0 = all cores
  int tileSize = 32;
  std::optional<PixelWindow> crop;  // default: the full frame
  bool progress = true;
};

struct RenderStats {
  double seconds = 0;
  RayCounters rays;
};

struct RenderResult {
  Film film;
  RenderStats stats;
};

RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt);

}  // namespace glint
