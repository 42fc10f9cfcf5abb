#include "render/tile_scheduler.h"

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <atomic>
#include <chrono>
#include <thread>

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

TEST(TileScheduler, WithThreadsCapsTheTilesAndTheRowLoopsInside) {
  // --threads caps the whole render: its tiles and the per-pixel loops between passes. With one
  // thread, all of them run on the calling thread; on the default arena TBB's workers would
  // take rows (each row waits 0.1 ms, long enough for a worker to steal).
  const std::vector<PixelWindow> tiles = makeTiles(PixelWindow{0, 64, 0, 64}, 8);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> rows{0}, tilesRun{0}, elsewhere{0};
  withThreads(1, [&] {
    forEachRow(0, 64, [&](int) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      ++rows;
      elsewhere += std::this_thread::get_id() != caller;
    });
    runTiles(tiles, 1, [&](size_t) {
      ++tilesRun;
      elsewhere += std::this_thread::get_id() != caller;
    });
  });
  EXPECT_EQ(rows.load(), 64);
  EXPECT_EQ(tilesRun.load(), 64);
  EXPECT_EQ(elsewhere.load(), 0);
}

}  // namespace
}  // namespace glint
