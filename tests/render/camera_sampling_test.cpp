#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "render/render_job.h"

namespace glint {
namespace {

// A chunk's rays come from several pixels' sets drawn side by side in the sampler's lanes; each
// must be the ray its sample makes alone from its own sets (the point at its index of its
// pixel half's pixel, lens and time sets), to the bit, or images would change with how samples
// fall into chunks (tile size, crop, pass). Every sampler, an odd spp (the halves' sets differ
// in size), pixels adding one, two and many samples, and a lens and an open shutter.
TEST(CameraSampling, ChunkRaysEqualEachSampleDrawnAlone) {
  Scene scene;
  scene.cameraDesc.eye = {0, 1, 4};
  scene.cameraDesc.lookAt = {0, 0, 0};
  scene.cameraDesc.apertureRadius = 0.1f;
  scene.cameraDesc.focusDistance = 4;
  scene.cameraDesc.shutterOpen = 0.25f;
  scene.cameraDesc.shutterClose = 0.75f;
  scene.features.motion = true;
  const Camera camera(scene.cameraDesc, 40, 30);
  const CameraSampling sampling(scene, camera);
  const int spp = 7;
  for (SamplerKind kind :
       {SamplerKind::Regular, SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol}) {
    const Sampler sampler(kind, spp, 17);
    // Runs of one pixel half's samples, as a pass lays them out: (x, y, half, first, count).
    struct Run {
      int x, y, half, first, count;
    };
    const std::vector<Run> runs = {{3, 4, 0, 0, 1},  {3, 4, 1, 0, 1},  {4, 4, 0, 1, 2},
                                   {4, 4, 1, 0, 3},  {5, 4, 0, 0, 4},  {6, 4, kWholeSet, 0, 7},
                                   {7, 4, 1, 2, 1},  {8, 4, 0, 3, 1},  {8, 4, 1, 1, 2},
                                   {9, 4, 0, 0, 1},  {10, 4, 0, 0, 1}, {11, 4, 0, 0, 1},
                                   {12, 4, 0, 0, 1}, {13, 4, 0, 0, 1}, {14, 4, 1, 2, 1},
                                   {15, 4, 0, 0, 4}, {15, 4, 1, 0, 3}};
    std::vector<SampleKey> keys;
    for (const Run& r : runs)
      for (int i = 0; i < r.count; ++i)
        keys.emplace_back(&sampler, r.x, r.y, r.first + i, sampler.pixelKey(r.x, r.y), r.half);
    ASSERT_GT(keys.size(), 32u);
    std::vector<Ray> rays(keys.size());
    CameraSampling::Points points;
    sampling.rays(keys.data(), static_cast<int>(keys.size()), rays.data(), points);
    for (size_t i = 0; i < keys.size(); ++i) {
      const SampleKey& k = keys[i];
      const Vec2f pixel = k.get2D(dimension(Dim::Pixel)), lens = k.get2D(dimension(Dim::Lens)),
                  time = k.get2D(dimension(Dim::Time));
      Ray alone;
      camera.generateRay(float(k.px) + pixel.x, float(k.py) + pixel.y, lens, alone);
      alone.time = 0.25f + (0.75f - 0.25f) * time.x;
      EXPECT_EQ(std::memcmp(&rays[i].o, &alone.o, sizeof alone.o), 0)
          << samplerName(kind) << " sample " << i;
      EXPECT_EQ(std::memcmp(&rays[i].d, &alone.d, sizeof alone.d), 0)
          << samplerName(kind) << " sample " << i;
      EXPECT_EQ(std::memcmp(&rays[i].time, &alone.time, sizeof alone.time), 0)
          << samplerName(kind) << " sample " << i;
    }
  }
}

}  // namespace
}  // namespace glint
