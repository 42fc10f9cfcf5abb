#pragma once
// Splits a pixel window into square tiles and runs them on TBB inside a task_arena capped at
// the requested thread count. Each tile is rendered by one task; results are reduced in tile
// order, so the output never depends on threads or scheduling.
#include <functional>
#include <memory>
#include <vector>

#include "film/film.h"

namespace glint {

// Row-major, or Morton (Z-order) over the tile grid: consecutive tiles are neighbours in the
// image, and TBB hands each thread a contiguous run of tile indices, so a thread keeps working
// on one region of the scene (its BVH nodes and triangles stay in cache).
enum class TileOrder { RowMajor, Morton };

std::vector<PixelWindow> makeTiles(const PixelWindow& window, int tileSize,
                                   TileOrder order = TileOrder::Morton);

// The tile edge actually used: `requested`, halved (not below 8) until there are at least
// kTilesPerThread tiles per thread, so that no thread idles long at the end of a pass.
inline constexpr int kTilesPerThread = 32;
int effectiveTileSize(const PixelWindow& window, int requested, int threads);

// An arena of `threads` threads (0 = all cores): the tiles and every other TBB loop that a body
// run on it starts share those threads, and no more. A render session keeps one for all its
// passes, so that its workers stay with it from one pass to the next.
class ThreadArena {
 public:
  explicit ThreadArena(int threads);
  ~ThreadArena();
  ThreadArena(const ThreadArena&) = delete;
  ThreadArena& operator=(const ThreadArena&) = delete;
  // Runs `body` on the arena; at once where the calling thread runs a body of it already.
  void run(const std::function<void()>& body) const;

 private:
  struct Arena;
  std::unique_ptr<Arena> arena_;
};

// Runs `body` on an arena of `threads` threads (0 = all cores) of its own.
void withThreads(int threads, const std::function<void()>& body);

// Runs renderTile(tileIndex) for every tile on `threads` threads (0 = all cores): called from
// the body of withThreads of as many threads, on its arena, else on an arena of its own.
void runTiles(const std::vector<PixelWindow>& tiles, int threads,
              const std::function<void(size_t tileIndex)>& renderTile);

// Calls row(y) for every y in [y0, y1) on the current arena's threads (inside withThreads, the
// render's), for per-pixel work whose rows write only their own results.
void forEachRow(int y0, int y1, const std::function<void(int y)>& row);

int defaultThreadCount();
// The threads a --threads value asks for: itself, or every core for 0.
int threadCount(int requested);

}  // namespace glint
