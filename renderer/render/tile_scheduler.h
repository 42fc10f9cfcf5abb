#pragma once
// Splits a pixel window into square tiles and runs them on TBB inside a task_arena capped at
// the requested thread count. Each tile is rendered by one task; results are reduced in tile
// order, so the output never depends on threads or scheduling.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "film/film.h"

namespace glint {

// Row-major, or Morton (Z-order) over the tile grid: consecutive tiles are neighbours in the
// image, so the threads, taking tiles in turn, work on one region of the scene at a time (its
// BVH nodes and triangles stay in the cache they share).
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

// When and on which thread one tile of a pass ran, its start from the pass's start
// (`glint render --stats-json`'s schedule).
struct TileTime {
  uint32_t tile = 0;  // its index in the pass's tiles
  float start = 0, seconds = 0;
  int32_t thread = 0;     // the thread's index in the arena
  float cpuSeconds = -1;  // its thread's CPU time in it, where asked for (TileSchedule::cpuTimes)
};

// The order in which a pass hands its tiles out (every tile in index order where empty), and
// where it notes their times (one per tile handed out, in that order; none where null).
// Thread CPU times leave out the time a busy machine takes a thread off its core.
struct TileSchedule {
  std::span<const uint32_t> order;
  std::vector<TileTime>* times = nullptr;
  bool cpuTimes = false;
};

// The tiles whose expected cost is above zero, the costliest first (ties in tile order): each
// thread takes the next tile when it finishes one, so a pass's last tiles are its cheapest and
// its threads finish close together, instead of waiting on one slow tile taken late.
std::vector<uint32_t> orderByCost(std::span<const double> costs);

// Runs renderTile(tileIndex) for every tile of `schedule`'s order on `threads` threads (0 = all
// cores), each thread taking the next tile in that order when it finishes one: called from the
// body of withThreads of as many threads, on its arena, else on an arena of its own.
void runTiles(const std::vector<PixelWindow>& tiles, int threads, const TileSchedule& schedule,
              const std::function<void(size_t tileIndex)>& renderTile);
// Every tile, in index order, its times not noted.
inline void runTiles(const std::vector<PixelWindow>& tiles, int threads,
                     const std::function<void(size_t tileIndex)>& renderTile) {
  runTiles(tiles, threads, TileSchedule{}, renderTile);
}

// Calls row(y) for every y in [y0, y1) on the current arena's threads (inside withThreads, the
// render's), for per-pixel work whose rows write only their own results.
void forEachRow(int y0, int y1, const std::function<void(int y)>& row);

// Calls block(begin, end) for every block of kBlockItems items of [0, count) on the current
// arena's threads: the same blocks for any thread count, for first writes of a frame's buffers
// (their pages then belong to the threads that render, not to one that zeroed them).
inline constexpr size_t kBlockItems = 4096;
void forEachBlock(size_t count, const std::function<void(size_t begin, size_t end)>& block);

// Writes `value` into every item, on the current arena's threads (forEachBlock).
template <class T>
void fillInBlocks(std::span<T> items, const T& value) {
  forEachBlock(items.size(), [&](size_t begin, size_t end) {
    std::fill(items.begin() + ptrdiff_t(begin), items.begin() + ptrdiff_t(end), value);
  });
}

int defaultThreadCount();
// The threads a --threads value asks for: itself, or every core for 0.
int threadCount(int requested);

}  // namespace glint
