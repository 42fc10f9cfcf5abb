#include "render/tile_scheduler.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>

#include "core/fp_env.h"

namespace glint {

namespace {

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

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

std::vector<uint32_t> orderByCost(std::span<const double> costs) {
  std::vector<uint32_t> order;
  for (size_t i = 0; i < costs.size(); ++i)
    if (costs[i] > 0) order.push_back(static_cast<uint32_t>(i));
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return costs[a] > costs[b]; });
  return order;
}

void runTiles(const std::vector<PixelWindow>& tiles, int threads, const TileSchedule& schedule,
              const std::function<void(size_t)>& renderTile) {
  const size_t count = schedule.order.empty() ? tiles.size() : schedule.order.size();
  if (schedule.times) schedule.times->assign(count, {});
  std::atomic<size_t> next{0};
  const auto passStart = std::chrono::steady_clock::now();
  const auto seconds = [&](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<float>(t - passStart).count();
  };
  // One taker per thread, each taking the next tile until none is left: a thread that joins
  // late finds the tiles taken and returns.
  const auto take = [&] {
    // Cheap, and TBB workers are not ours to set up; restored after, since the calling thread
    // takes tiles too.
    const FlushToZeroScope flushToZero;
    for (size_t k; (k = next.fetch_add(1, std::memory_order_relaxed)) < count;) {
      const size_t tile = schedule.order.empty() ? k : schedule.order[k];
      const auto start = std::chrono::steady_clock::now();
      const double cpuStart = schedule.cpuTimes ? threadCpuSeconds() : 0;
      renderTile(tile);
      if (schedule.times)
        (*schedule.times)[k] = {
            static_cast<uint32_t>(tile), seconds(start),
            seconds(std::chrono::steady_clock::now()) - seconds(start),
            tbb::this_task_arena::current_thread_index(),
            schedule.cpuTimes ? static_cast<float>(threadCpuSeconds() - cpuStart) : -1.0f};
    }
  };
  const auto run = [&] {
    const int takers = tArenaThreads > 0 ? tArenaThreads : threadCount(threads);
    tbb::parallel_for(
        0, takers, [&](int) { take(); }, tbb::simple_partitioner());
  };
  if (tArenaThreads == threadCount(threads))
    run();
  else
    withThreads(threads, run);
}

void forEachBlock(size_t count, const std::function<void(size_t, size_t)>& block) {
  const size_t blocks = (count + kBlockItems - 1) / kBlockItems;
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    block(b * kBlockItems, std::min(count, (b + 1) * kBlockItems));
  });
}

void forEachRow(int y0, int y1, const std::function<void(int)>& row) {
  tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) row(y);
  });
}

}  // namespace glint
