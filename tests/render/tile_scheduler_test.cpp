#include "render/tile_scheduler.h"

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <tbb/task_arena.h>

#include <atomic>

namespace glint {
namespace {

TEST(TileScheduler, TilesTraceWithFlushToZeroAndTheCallerKeepsItsModes) {
  // Embree asks every tracing thread for flush-to-zero and denormals-are-zero; the calling
  // thread runs tiles too (one thread: it runs them all), and must get its own modes back, or
  // its arithmetic after a render loses denormals.
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_OFF);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_OFF);
  const std::vector<PixelWindow> tiles = makeTiles(PixelWindow{0, 64, 0, 64}, 16);
  ASSERT_EQ(tiles.size(), 16u);  // 64 / 16 = 4 tiles a side
  std::atomic<int> flushing{0};
  for (const int threads : {1, 2}) {
    flushing = 0;
    runTiles(tiles, threads, [&](size_t) {
      flushing += _MM_GET_FLUSH_ZERO_MODE() == _MM_FLUSH_ZERO_ON &&
                  _MM_GET_DENORMALS_ZERO_MODE() == _MM_DENORMALS_ZERO_ON;
    });
    EXPECT_EQ(flushing.load(), 16) << threads << " threads";
    EXPECT_EQ(_MM_GET_FLUSH_ZERO_MODE(), _MM_FLUSH_ZERO_OFF) << threads << " threads";
    EXPECT_EQ(_MM_GET_DENORMALS_ZERO_MODE(), _MM_DENORMALS_ZERO_OFF) << threads << " threads";
  }
}

TEST(TileScheduler, TilesShrinkUntilEveryThreadHasItsShare) {
  // At least kTilesPerThread (32) tiles a thread, halving from the size asked, never below 8.
  const PixelWindow frame{0, 640, 0, 400};
  EXPECT_EQ(effectiveTileSize(frame, 32, 2), 32);   // 20 x 13 = 260 tiles >= 64
  EXPECT_EQ(effectiveTileSize(frame, 32, 16), 16);  // 260 < 512; 40 x 25 = 1000 >= 512
  EXPECT_EQ(effectiveTileSize(frame, 32, 64), 8);   // 1000 < 2048: down to the floor of 8
  EXPECT_EQ(effectiveTileSize(frame, 64, 2), 64);   // 10 x 7 = 70 >= 64
  EXPECT_EQ(effectiveTileSize(PixelWindow{0, 4, 0, 4}, 32, 1), 8);  // one tile, at the floor
}

TEST(TileScheduler, WithThreadsCapsTheTilesAndEveryLoopInside) {
  // --threads is a cap on the whole render: its tiles and the per-pixel loops between passes.
  const std::vector<PixelWindow> tiles = makeTiles(PixelWindow{0, 64, 0, 64}, 8);
  std::atomic<int> highest{-1};
  int concurrency = 0;
  withThreads(2, [&] {
    concurrency = tbb::this_task_arena::max_concurrency();
    runTiles(tiles, 2, [&](size_t) {
      const int index = tbb::this_task_arena::current_thread_index();
      int seen = highest.load();
      while (index > seen && !highest.compare_exchange_weak(seen, index)) {
      }
    });
  });
  EXPECT_EQ(concurrency, 2);
  EXPECT_GE(highest.load(), 0);
  EXPECT_LT(highest.load(), 2);
}

}  // namespace
}  // namespace glint
