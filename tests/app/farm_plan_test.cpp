// Farm plans (app/farm_plan.h, docs/farm.md): tile grids that cover the frame exactly, frame
// ranges and `####` frame names.
#include "app/farm_plan.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace glint {
namespace {

// How many tiles cover each pixel: 1 everywhere means no hole and no overlap.
std::vector<int> coverage(const std::vector<PixelWindow>& tiles, int width, int height) {
  std::vector<int> n(size_t(width) * size_t(height), 0);
  for (const PixelWindow& t : tiles)
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) ++n[size_t(y) * size_t(width) + size_t(x)];
  return n;
}

TEST(FarmPlan, FourTilesOfA3to2FrameAreItsQuarters) {
  // 96 × 64 in 4: 2 × 2 tiles are 48 × 32 (aspect 1.5, |ln| = 0.41), nearer square than 4 × 1
  // (24 × 64, |ln 0.375| = 0.98) or 1 × 4 (96 × 16, |ln 6| = 1.79). Row-major order.
  int columns = 0, rows = 0;
  const auto t = farmTiles(96, 64, 4, &columns, &rows);
  EXPECT_EQ(columns, 2);
  EXPECT_EQ(rows, 2);
  ASSERT_EQ(t.size(), 4u);
  const int expected[4][4] = {{0, 48, 0, 32}, {48, 96, 0, 32}, {0, 48, 32, 64}, {48, 96, 32, 64}};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(t[k].x0, expected[k][0]) << k;
    EXPECT_EQ(t[k].x1, expected[k][1]) << k;
    EXPECT_EQ(t[k].y0, expected[k][2]) << k;
    EXPECT_EQ(t[k].y1, expected[k][3]) << k;
  }
}

TEST(FarmPlan, TilesCoverEveryPixelOnceForAnyCount) {
  // Uneven divisions (640 / 3, 480 / 7, a prime count, 1 tile) still cover each pixel exactly
  // once, because neighbouring tiles share the edge ⌊i·W/columns⌋.
  for (int count : {1, 2, 3, 4, 6, 7, 12, 13, 64}) {
    for (auto [w, h] : {std::pair{640, 480}, std::pair{97, 61}, std::pair{13, 1000}}) {
      const auto t = farmTiles(w, h, count);
      ASSERT_EQ(t.size(), size_t(count));
      const auto n = coverage(t, w, h);
      EXPECT_TRUE(std::all_of(n.begin(), n.end(), [](int c) { return c == 1; }))
          << count << " tiles of " << w << "x" << h;
      for (const PixelWindow& tile : t) EXPECT_GT(tile.area(), 0);
    }
  }
}

TEST(FarmPlan, PrimeCountsBecomeStripsAlongTheLongSide) {
  // 7 tiles of 700 × 100: 7 × 1 gives 100 × 100 squares.
  int columns = 0, rows = 0;
  farmTiles(700, 100, 7, &columns, &rows);
  EXPECT_EQ(columns, 7);
  EXPECT_EQ(rows, 1);
}

TEST(FarmPlan, ImpossibleTileCountsAreUsageErrors) {
  EXPECT_THROW(farmTiles(640, 480, 0, nullptr, nullptr), UsageError);
  // 5 non-empty tiles cannot fit a 2 × 2 frame (5 is prime: 5 × 1 or 1 × 5).
  try {
    farmTiles(2, 2, 5);
    FAIL() << "5 tiles of 2x2 were accepted";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "5 tiles do not fit a 2x2 frame as a grid of non-empty tiles");
  }
}

TEST(FarmPlan, FrameRanges) {
  const FrameRange r = parseFrameRange("1-3", "--frames");
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.last, 3);
  EXPECT_EQ(r.count(), 3);
  EXPECT_TRUE(r.contains(2));
  EXPECT_FALSE(r.contains(4));
  const FrameRange one = parseFrameRange("17", "--frames");
  EXPECT_EQ(one.first, 17);
  EXPECT_EQ(one.last, 17);
  for (const char* bad : {"3-1", "a-b", "-1", "1-", "", "1-2-3", "1.5", " 1"})
    EXPECT_THROW(parseFrameRange(bad, "--frames"), UsageError) << bad;
  try {
    parseFrameRange("3-1", "--frames");
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(),
                 "--frames: the first frame must not come after the last, got \"3-1\" (write A-B "
                 "or A)");
  }
}

TEST(FarmPlan, FrameNamesReplaceTheLastRunOfHashes) {
  EXPECT_EQ(frameFileName("out/shot.####.exr", 7), "out/shot.0007.exr");
  EXPECT_EQ(frameFileName("shot.####.exr", 12345), "shot.12345.exr");  // longer: in full
  EXPECT_EQ(frameFileName("shot.#.exr", 12), "shot.12.exr");
  EXPECT_EQ(frameFileName("a.##.b.###.exr", 5), "a.##.b.005.exr");
  EXPECT_EQ(frameFileName("shot.exr", 3), "shot.exr");
  // printf-style, as Nuke and ffmpeg write sequences; '#' wins where both appear.
  EXPECT_EQ(frameFileName("out/shot.%04d.exr", 7), "out/shot.0007.exr");
  EXPECT_EQ(frameFileName("shot.%d.exr", 7), "shot.7.exr");
  EXPECT_EQ(frameFileName("shot.%4d.exr", 7), "shot.0007.exr");  // zero-padded all the same
  EXPECT_EQ(frameFileName("50%.%03d.exr", 12345), "50%.12345.exr");
  EXPECT_EQ(frameFileName("a.%04d.####.exr", 3), "a.%04d.0003.exr");
  EXPECT_EQ(frameFileName("dir%04d/shot.exr", 3), "dir%04d/shot.exr");  // not in the file name
  EXPECT_FALSE(hasFrameDigits("100%.exr"));
  // As printf reads them: "%%" is a literal '%', in a printf-style name only.
  EXPECT_EQ(frameFileName("100%%.%04d.exr", 7), "100%.0007.exr");
  EXPECT_EQ(frameFileName("a.%04d.%%%%.exr", 7), "a.0007.%%.exr");
  EXPECT_EQ(frameFileName("a.%%d.%d.exr", 7), "a.%d.7.exr");
  EXPECT_EQ(frameFileName("e.%d_%03d.exr", 7), "e.7_007.exr");  // every field, as printf
  EXPECT_FALSE(hasFrameDigits("a.%%d.exr"));  // "%%d" is "%d" written out, not a field
  EXPECT_EQ(frameFileName("100%%.####.exr", 7), "100%%.0007.exr");  // '#' names are literal
  EXPECT_EQ(frameFileName("50%%/a.%d.exr", 7), "50%%/a.7.exr");     // directories too
  // Only the file name counts: a '#' in a directory is not a frame number.
  EXPECT_EQ(frameFileName("take#2/shot.exr", 3), "take#2/shot.exr");
  EXPECT_FALSE(hasFrameDigits("take#2/shot.exr"));
  EXPECT_TRUE(hasFrameDigits("take#2/shot.##.exr"));
}

}  // namespace
}  // namespace glint
