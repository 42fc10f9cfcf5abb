#include "render/tile_scheduler.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/fp_env.h"

namespace glint {

std::vector<PixelWindow> makeTiles(const PixelWindow& window, int tileSize) {
  // Row-major tile order: neighbouring tasks share scanlines of the scene, which is what
  // primary-ray coherence needs; a space-filling order is left to the scheduler issue.
  std::vector<PixelWindow> tiles;
  for (int y = window.y0; y < window.y1; y += tileSize)
    for (int x = window.x0; x < window.x1; x += tileSize)
      tiles.push_back({x, std::min(x + tileSize, window.x1), y, std::min(y + tileSize, window.y1)});
  return tiles;
}

int defaultThreadCount() { return tbb::info::default_concurrency(); }

void runTiles(const std::vector<PixelWindow>& tiles, int threads,
              const std::function<void(size_t)>& renderTile) {
  tbb::task_arena arena(threads > 0 ? threads : defaultThreadCount());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        enableFlushToZero();  // cheap, and TBB workers are not ours to set up
                        for (size_t i = r.begin(); i != r.end(); ++i) renderTile(i);
                      });
  });
}

}  // namespace glint
