#include "render/tile_scheduler.h"

#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

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

}  // namespace
}  // namespace glint
