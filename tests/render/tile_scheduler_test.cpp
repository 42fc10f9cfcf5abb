#include "render/tile_scheduler.h"

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "core/unwritten_allocator.h"
#include "render/pixel_estimate.h"

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

TEST(TileScheduler, TilesByCostAreTheCostliestFirstEachTileWithWorkOnce) {
  // Costs 3, 0, 5, 3, 1, 5: tile 1 has no work and is left out; 5s before 3s before 1, ties in
  // tile order (2 before 5, 0 before 3), so the order depends on the costs alone.
  const std::vector<double> costs = {3, 0, 5, 3, 1, 5};
  const std::vector<uint32_t> expected = {2, 5, 0, 3, 4};
  EXPECT_EQ(orderByCost(costs), expected);
  EXPECT_EQ(orderByCost(costs), orderByCost(costs));
  EXPECT_TRUE(orderByCost(std::vector<double>(4, 0.0)).empty());  // a pass with nothing to do
}

TEST(TileScheduler, EveryTileOfTheOrderRunsOnceAndItsTimeIsNotedInThatOrder) {
  // 64 tiles, 37 of them handed out in reverse: each of those runs exactly once (a count per
  // tile), the others never, and the times list them in the order given, one each.
  const std::vector<PixelWindow> tiles = makeTiles(PixelWindow{0, 64, 0, 64}, 8);
  std::vector<uint32_t> order;
  for (uint32_t i = 37; i-- > 0;) order.push_back(i);
  for (const int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> runs(tiles.size());
    std::vector<TileTime> times;
    runTiles(tiles, threads, TileSchedule{order, &times}, [&](size_t i) { ++runs[i]; });
    for (size_t i = 0; i < tiles.size(); ++i)
      EXPECT_EQ(runs[i].load(), i < 37 ? 1 : 0) << "tile " << i << ", " << threads << " threads";
    ASSERT_EQ(times.size(), order.size()) << threads << " threads";
    for (size_t k = 0; k < order.size(); ++k) {
      EXPECT_EQ(times[k].tile, order[k]) << k;
      EXPECT_GE(times[k].thread, 0) << k;
      EXPECT_LT(times[k].thread, threads) << k;
    }
  }
}

TEST(TileScheduler, BlocksAreTheSameForAnyThreadCount) {
  // 10000 items in blocks of kBlockItems (4096): [0, 4096), [4096, 8192), [8192, 10000) for 1,
  // 2 and 7 threads, each once.
  const std::set<std::pair<size_t, size_t>> expected = {{0, 4096}, {4096, 8192}, {8192, 10000}};
  for (const int threads : {1, 2, 7}) {
    std::set<std::pair<size_t, size_t>> blocks;
    std::mutex m;
    withThreads(threads, [&] {
      forEachBlock(10000, [&](size_t begin, size_t end) {
        const std::lock_guard<std::mutex> lock(m);
        EXPECT_TRUE(blocks.emplace(begin, end).second) << begin;
      });
    });
    EXPECT_EQ(blocks, expected) << threads << " threads";
  }
}

TEST(TileScheduler, StatesWrittenInBlocksAreTheStatesMadeAtZero) {
  // A frame's pixel states filled block by block on 1, 2 and 7 threads hold what states made as
  // values hold, every field zero: the memory first holds a planted state (99 samples a half),
  // so a block left unwritten would show.
  const size_t count = 3 * kBlockItems + 17;
  PixelEstimate planted;
  planted.half[0].count = planted.half[1].count = 99;
  planted.half[1].mean[2] = 0.5;
  for (const int threads : {1, 2, 7}) {
    PixelEstimates states(count, planted);
    withThreads(threads, [&] { fillInBlocks(std::span<PixelEstimate>(states), PixelEstimate{}); });
    const std::vector<PixelEstimate> zero(count);
    ASSERT_EQ(states.size(), count);
    for (size_t i = 0; i < count; ++i)
      for (int h = 0; h < 2; ++h) {
        const HalfEstimate &got = states[i].half[h], &want = zero[i].half[h];
        ASSERT_EQ(got.count, want.count) << i;
        ASSERT_EQ(got.rays, want.rays) << i;
        ASSERT_EQ(got.alpha, want.alpha) << i;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(got.mean[c], want.mean[c]) << i;
      }
  }
}

}  // namespace
}  // namespace glint
