#include "render/render_job.h"

#include <atomic>
#include <chrono>
#include <string>

#include "camera/camera.h"
#include "core/log.h"
#include "core/sampler.h"
#include "integrator/whitted.h"
#include "render/aov_accumulator.h"
#include "render/progress.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {
constexpr int kMaxLoggedNonfinite = 5;
}

RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const RenderSettings& rs = scene.render;
  const PixelWindow window = opt.crop.value_or(PixelWindow{0, rs.width, 0, rs.height});
  Film film(rs.width, rs.height, window);
  const Camera camera(scene.cameraDesc, rs.width, rs.height);
  const Sampler sampler(rs.sampler, rs.spp, rs.seed);
  const WhittedIntegrator integrator(scene, accel);

  const float shutterOpen = scene.cameraDesc.shutterOpen;
  const float shutterClose = scene.cameraDesc.shutterClose;
  const bool openShutter = scene.features.motion && shutterClose > shutterOpen;

  const int threads = opt.threads > 0 ? opt.threads : defaultThreadCount();
  const int tileSize = effectiveTileSize(window, opt.tileSize, threads);
  const std::vector<PixelWindow> tiles = makeTiles(window, tileSize, opt.tileOrder);
  std::atomic<bool> skipped{false};
  std::vector<RayCounters> tileCounters(tiles.size());
  Progress progress(window.area(), opt.progress);
  std::atomic<int> loggedNonfinite{0};
  // AOV work happens only when AOVs are asked for (leave out what is not needed).
  const AovLayout aovLayout = AovLayout::create(opt.aovs, scene.lights.size(), film);
  const bool aovs = opt.aovs.any();
  const bool aovSamples = opt.aovs.needsSamples();
  const Vec3f viewAxis = -camera.w();

  runTiles(tiles, threads, [&](size_t tileIndex) {
    if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) {
      skipped = true;
      return;
    }
    const PixelWindow& tile = tiles[tileIndex];
    RayCounters& counters = tileCounters[tileIndex];
    PixelAovs pixelAovs(aovLayout);
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        double sum[4] = {0, 0, 0, 0};
        if (aovs) pixelAovs.begin();
        for (int s = 0; s < rs.spp; ++s) {
          const SampleKey key{&sampler, x, y, s};
          const Vec2f u = sampler.pixelSample(x, y, s);
          // The lens dimension is drawn only when there is a lens (leave out what is unused).
          const Vec2f lens = camera.hasLens() ? key.get2D(dimension(Dim::Lens)) : Vec2f{};
          Ray ray =
              camera.generateRay(static_cast<float>(x) + u.x, static_cast<float>(y) + u.y, lens);
          // The time dimension is drawn only when something moves and the shutter is open.
          ray.time = openShutter ? shutterOpen + (shutterClose - shutterOpen) *
                                                     key.get2D(dimension(Dim::Time)).x
                                 : shutterOpen;
          AovSample aov;
          aov.viewAxis = viewAxis;
          Radiance r = integrator.trace(ray, key, counters, aovSamples ? &aov : nullptr);
          if (opt.sampleHook) opt.sampleHook(x, y, r);
          if (!r.L.isFinite()) r.L = {}, r.valid = false;
          if (aovs) pixelAovs.add(r, aov);  // an invalid sample adds no AOV record
          if (!r.valid) {
            // A non-finite sample never reaches the film: it counts as black.
            ++counters.nonfiniteSamples;
            if (loggedNonfinite.fetch_add(1) < kMaxLoggedNonfinite)
              log::warning("non-finite sample at pixel (" + std::to_string(x) + ", " +
                           std::to_string(y) + ") sample " + std::to_string(s));
            sum[3] += r.alpha;
            continue;
          }
          sum[0] += r.L.r;
          sum[1] += r.L.g;
          sum[2] += r.L.b;
          sum[3] += r.alpha;
        }
        const double inv = 1.0 / rs.spp;
        film.setPixel(x, y, sum[0] * inv, sum[1] * inv, sum[2] * inv, sum[3] * inv);
        if (aovs) pixelAovs.end(film, x, y);
      }
    progress.advance(tile.area(), counters.total());
  });
  progress.finish();

  RenderResult result{std::move(film), {}, skipped.load(), tileSize};
  for (const RayCounters& c : tileCounters) result.stats.rays += c;
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace glint
