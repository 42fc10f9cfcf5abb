#include "render/tile_scheduler.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>

#include "core/fp_env.h"

namespace glint {

namespace {

// Interleaves the bits of x and y (x in the even bits): the Morton code of a tile.
uint64_t morton(uint32_t x, uint32_t y) {
  uint64_t code = 0;
  for (int b = 0; b < 32; ++b)
    code |= (uint64_t((x >> b) & 1) << (2 * b)) | (uint64_t((y >> b) & 1) << (2 * b + 1));
  return code;
}

}  // namespace

std::vector<PixelWindow> makeTiles(const PixelWindow& window, int tileSize, TileOrder order) {
  struct Keyed {
    uint64_t key;
    PixelWindow tile;
  };
  std::vector<Keyed> keyed;
  for (int y = window.y0, ty = 0; y < window.y1; y += tileSize, ++ty)
    for (int x = window.x0, tx = 0; x < window.x1; x += tileSize, ++tx)
      keyed.push_back(
          {order == TileOrder::Morton ? morton(uint32_t(tx), uint32_t(ty)) : keyed.size(),
           {x, std::min(x + tileSize, window.x1), y, std::min(y + tileSize, window.y1)}});
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const Keyed& a, const Keyed& b) { return a.key < b.key; });
  std::vector<PixelWindow> tiles;
  for (const Keyed& k : keyed) tiles.push_back(k.tile);
  return tiles;
}

int effectiveTileSize(const PixelWindow& window, int requested, int threads) {
  int size = requested;
  const auto tilesAt = [&](int s) {
    return int64_t((window.width() + s - 1) / s) * ((window.height() + s - 1) / s);
  };
  // Every pass ends when its last tile does, so tiles must be small against a thread's share
  // of the frame (docs/performance.md, Scaling with cores).
  while (size > 8 && tilesAt(size) < kTilesPerThread * int64_t(threads))
    size = std::max(8, size / 2);
  return size;
}

int defaultThreadCount() { return tbb::info::default_concurrency(); }

int threadCount(int requested) { return requested > 0 ? requested : defaultThreadCount(); }

namespace {
// The threads of the arena whose body this thread runs, and that arena; 0 and null outside one.
thread_local int tArenaThreads = 0;
thread_local const ThreadArena* tArena = nullptr;
}  // namespace

struct ThreadArena::Arena {
  int threads;
  tbb::task_arena arena;
  explicit Arena(int count) : threads(count), arena(count) {}
};

ThreadArena::ThreadArena(int threads) : arena_(std::make_unique<Arena>(threadCount(threads))) {}
ThreadArena::~ThreadArena() = default;

void ThreadArena::run(const std::function<void()>& body) const {
  if (tArena == this) {
    body();
    return;
  }
  arena_->arena.execute([&] {
    struct Mark {
      int outerThreads = tArenaThreads;
      const ThreadArena* outer = tArena;
      ~Mark() { tArenaThreads = outerThreads, tArena = outer; }
    } restoredOnExit;
    tArenaThreads = arena_->threads;
    tArena = this;
    body();
  });
}

void withThreads(int threads, const std::function<void()>& body) { ThreadArena(threads).run(body); }

void runTiles(const std::vector<PixelWindow>& tiles, int threads,
              const std::function<void(size_t)>& renderTile) {
  const auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        // Cheap, and TBB workers are not ours to set up; restored after, since
                        // the calling thread runs ranges too.
                        const FlushToZeroScope flushToZero;
                        for (size_t i = r.begin(); i != r.end(); ++i) renderTile(i);
                      });
  };
  if (tArenaThreads == threadCount(threads))
    run();
  else
    withThreads(threads, run);
}

void forEachRow(int y0, int y1, const std::function<void(int)>& row) {
  tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) row(y);
  });
}

}  // namespace glint
