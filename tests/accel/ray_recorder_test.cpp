// RayRecorder (glint bench's Embree limit): which queries it keeps, and that it keeps a coherent
// batch whole, in order, marked with its size, so the bench can replay it as it was traced.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "accel/ray_recorder.h"
#include "test_util.h"

namespace glint {
namespace {

TEST(RayRecorder, KeepsOneQueryInStrideAndEachBatchWhole) {
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
      "materials": {"m": {"type": "phong"}},
      "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  constexpr uint64_t kStride = 4;
  RayRecorder recorder(*embree, kStride);
  // 1000 single queries and 1000 batches of 8 (alternating intersect and occluded), each ray
  // told apart by its tMax; the batches aim at the sphere, so the answers are not all misses.
  constexpr int kQueries = 1000, kBatch = 8;
  int id = 0;
  auto nextRay = [&] {
    Ray r;
    r.o = {0.1f * float(id % 7), 0.1f * float(id % 5), 5};
    r.d = {0, 0, -1};
    r.tMax = 100 + float(id++);
    return r;
  };
  int expectedHits = 0, answeredHits = 0;
  for (int q = 0; q < kQueries; ++q) {
    const Ray one = nextRay();
    if (q % 2) {
      EXPECT_EQ(recorder.occluded(one), embree->occluded(one));
    } else {
      EXPECT_EQ(bool(recorder.intersect(one)), bool(embree->intersect(one)));
    }
    Ray batch[kBatch];
    for (Ray& r : batch) r = nextRay();
    Hit hits[kBatch];
    bool blocked[kBatch];
    if (q % 2) {
      recorder.occludedCoherent(batch, blocked, kBatch);
      for (int i = 0; i < kBatch; ++i)
        answeredHits += blocked[i], expectedHits += embree->occluded(batch[i]);
    } else {
      recorder.intersectCoherent(batch, hits, kBatch);
      for (int i = 0; i < kBatch; ++i)
        answeredHits += bool(hits[i]), expectedHits += bool(embree->intersect(batch[i]));
    }
  }
  // The decorator answers as the backend does (every ray below hits the sphere's disc).
  EXPECT_EQ(answeredHits, expectedHits);
  EXPECT_EQ(expectedHits, kQueries * kBatch);

  const std::vector<RecordedRay> kept = recorder.take();
  int singles = 0, batches = 0;
  for (size_t i = 0; i < kept.size();) {
    const RecordedRay& first = kept[i];
    ASSERT_TRUE(first.query == 1 || first.query == uint32_t(kBatch)) << "entry " << i;
    // Rays were numbered by tMax in the order made: a batch's rays follow one another.
    for (uint32_t k = 1; k < first.query; ++k) {
      ASSERT_LT(i + k, kept.size());
      EXPECT_EQ(kept[i + k].query, 0u);
      EXPECT_EQ(kept[i + k].ray.tMax, first.ray.tMax + float(k));
      EXPECT_EQ(kept[i + k].occlusion, first.occlusion);
    }
    (first.query == 1 ? singles : batches) += 1;
    i += first.query;
  }
  // One query in kStride of 2000, picked by a hash: as a fair coin of p = 1/4 per query the
  // count of kept queries has mean 500 and standard deviation √(2000·¼·¾) ≈ 19.4; 5σ bounds.
  EXPECT_NEAR(singles + batches, 500, 97);
  EXPECT_GT(singles, 150);  // both kinds of query kept (mean 250 each, σ ≈ 13.7)
  EXPECT_GT(batches, 150);
  EXPECT_TRUE(recorder.take().empty());  // taking empties it
}

}  // namespace
}  // namespace glint
