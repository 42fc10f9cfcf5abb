// A pixel's camera hits are shaded together (WhittedKernel::traceCameraHits): their shadow rays
// are queued and traced in one pass. That must change nothing: every sample's radiance, alpha
// and AOV record equal what trace() gives for it alone, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "camera/camera.h"
#include "integrator/whitted.h"
#include "io/scene_loader.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

bool sameBits(const Rgb& a, const Rgb& b) { return std::memcmp(&a, &b, sizeof(Rgb)) == 0; }

bool sameRecord(const AovSample& a, const AovSample& b) {
  bool same = a.hit == b.hit && a.depth == b.depth && a.objectId == b.objectId &&
              sameBits(a.albedo, b.albedo) && sameBits(a.direct, b.direct);
  for (int i = 0; i < AovSet::kMaxLights; ++i)
    same = same && sameBits(a.perLight[i], b.perLight[i]);
  return same;
}

// Compares the two paths over a small frame of `scene` with the general kernel; returns how many
// samples were compared and adds a failure per sample that differs. Like renderTile, one call
// of traceCameraHits takes all the samples of 64 / spp pixels along a row (at least one).
int compareBatchedWithOneByOne(const Scene& scene, const std::string& what) {
  constexpr int kWidth = 24, kHeight = 16;
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const Camera camera(scene.cameraDesc, kWidth, kHeight);
  const Sampler sampler(scene.render.sampler, scene.render.spp, scene.render.seed);
  const CameraSampling cameraSampling(scene, camera);
  const WhittedIntegrator integrator(scene, *accel);
  const int spp = scene.render.spp, pixelsPerCall = std::max(1, kCameraChunk / spp);
  const int n = spp * pixelsPerCall;
  std::vector<SampleKey> keys(n);
  std::vector<Ray> rays(n);
  std::vector<Hit> hits(n);
  std::vector<Radiance> batched(n);
  std::vector<AovSample> records(n);
  std::vector<AovSample*> recordOf(n);
  const auto scratch = std::make_unique<WhittedIntegrator::Scratch>();
  int compared = 0, differing = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x0 = 0; x0 < kWidth; x0 += pixelsPerCall) {
      const int count = std::min(pixelsPerCall, kWidth - x0) * spp;
      for (int i = 0; i < count; ++i) {
        keys[i] = SampleKey(&sampler, x0 + i / spp, y, i % spp);
        rays[i] = cameraSampling.ray(keys[i]);
        records[i] = AovSample{};
        records[i].viewAxis = -camera.w();
        recordOf[i] = &records[i];
      }
      accel->intersectCoherent(rays.data(), hits.data(), static_cast<size_t>(count));
      RayCounters batchedCounters, aloneCounters;
      integrator.traceCameraHits(rays.data(), hits.data(), keys.data(), count, batched.data(),
                                 recordOf.data(), batchedCounters, *scratch);
      for (int i = 0; i < count; ++i) {
        AovSample record;
        record.viewAxis = -camera.w();
        const Radiance alone = integrator.trace(rays[i], hits[i], keys[i], aloneCounters, &record);
        const bool same = sameBits(alone.L, batched[i].L) && alone.alpha == batched[i].alpha &&
                          alone.valid == batched[i].valid && sameRecord(record, records[i]);
        if (!same && ++differing <= 3)
          ADD_FAILURE() << what << ": pixel (" << keys[i].px << ", " << y << ") sample "
                        << keys[i].index << " differs: " << alone.L.r << " " << alone.L.g << " "
                        << alone.L.b << " alone, " << batched[i].L.r << " " << batched[i].L.g << " "
                        << batched[i].L.b << " batched";
        ++compared;
      }
      // The same rays, too, kind by kind.
      EXPECT_EQ(batchedCounters.camera, aloneCounters.camera) << what;
      EXPECT_EQ(batchedCounters.shadow, aloneCounters.shadow) << what;
      EXPECT_EQ(batchedCounters.reflection, aloneCounters.reflection) << what;
      EXPECT_EQ(batchedCounters.refraction, aloneCounters.refraction) << what;
    }
  EXPECT_EQ(differing, 0) << what;
  return compared;
}

// At 16 spp a call holds 4 pixels; at 3 spp, 21 (the last call of a row fewer).
TEST(BatchedShading, EveryBundledSceneMatchesOneSampleAtATime) {
  int scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(GLINT_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    for (const int spp : {16, 3}) {
      Scene scene = loadSceneFile(e.path().string());
      scene.render.spp = std::min(scene.render.spp, spp);
      EXPECT_GT(compareBatchedWithOneByOne(
                    scene, e.path().filename().string() + " at " + std::to_string(spp) + " spp"),
                0);
    }
    ++scenes;
  }
  EXPECT_GE(scenes, 10);
}

// The shadow-ray queue holds 512 rays. With 2 area lights of `samples` each and 16 spp (4
// pixels a call), a call queues 64 × 2 × samples rays: 40 samples fill the queue mid-call
// (traced, then refilled); 300 give one hit more rays than the queue holds (that hit is shaded
// on its own). The lights' points for a call's samples are drawn together into room for 2048:
// 16 samples (1024 points a light) fit for both lights, 24 for the first light only (the
// second's points are drawn per hit), 40 for neither.
TEST(BatchedShading, AQueueThatFillsOrOverflowsChangesNothing) {
  for (const int samples : {1, 16, 24, 40, 300}) {
    Scene scene = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/soft_shadows.json");
    scene.render.spp = 16;
    int areaLights = 0;
    for (Light& light : scene.lights) {
      if (auto* q = std::get_if<QuadLight>(&light)) q->samples = samples, ++areaLights;
      if (auto* d = std::get_if<DiskLight>(&light)) d->samples = samples, ++areaLights;
    }
    ASSERT_EQ(areaLights, 2);
    EXPECT_GT(compareBatchedWithOneByOne(scene, std::to_string(samples) + " samples"), 0);
  }
}

// The render makes a pixel's camera rays as a run (CameraSampling::rays draws each dimension's
// points in one call, in vector lanes for power-of-two sets); one at a time they come from the
// sampler's general code. Both must give the same rays bit for bit, with a lens and a shutter
// (lens and time dimensions drawn), for runs that start mid-pixel and for sets that are not
// powers of two.
TEST(BatchedShading, CameraRaysOfARunMatchOneAtATime) {
  for (const char* file : {"depth_of_field.json", "motion_blur.json", "default.json"})
    for (const int spp : {16, 12, 64}) {
      Scene scene = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/" + file);
      const Camera camera(scene.cameraDesc, 32, 24);
      const Sampler sampler(scene.render.sampler, spp, scene.render.seed);
      const CameraSampling cameraSampling(scene, camera);
      for (const int first : {0, 5}) {
        std::vector<SampleKey> keys;
        for (int i = first; i < spp; ++i) keys.emplace_back(&sampler, 7, 3, i);
        std::vector<Ray> run(keys.size());
        CameraSampling::Points points;
        cameraSampling.rays(keys.data(), static_cast<int>(keys.size()), run.data(), points);
        for (size_t i = 0; i < keys.size(); ++i) {
          const Ray alone = cameraSampling.ray(keys[i]);
          EXPECT_TRUE(std::memcmp(&alone.o, &run[i].o, sizeof alone.o) == 0 &&
                      std::memcmp(&alone.d, &run[i].d, sizeof alone.d) == 0 &&
                      alone.time == run[i].time)
              << file << " spp " << spp << " sample " << keys[i].index;
        }
      }
    }
}

}  // namespace
}  // namespace glint
