// The bookkeeping of `glint bench --intersection-share` (app/intersection_share.h): the replay
// hands the backend exactly the queries the render made, each once per pass, as the render made
// them (batches whole). Its timings are benchmarks and are not tested.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <tuple>
#include <vector>

#include "accel/ray_recorder.h"
#include "app/render_bench.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// Passes every query to `inner` and notes it: the ray, whether it asked for occlusion, and the
// size of the call it came in.
class QueryLog final : public Accelerator {
 public:
  explicit QueryLog(const Accelerator& inner) : inner_(inner) {}
  Hit intersect(const Ray& r) const override {
    note(&r, 1, false);
    return inner_.intersect(r);
  }
  bool occluded(const Ray& r) const override {
    note(&r, 1, true);
    return inner_.occluded(r);
  }
  void intersectCoherent(const Ray* rays, Hit* hits, size_t n) const override {
    note(rays, n, false);
    inner_.intersectCoherent(rays, hits, n);
  }
  void occludedCoherent(const Ray* rays, bool* blocked, size_t n) const override {
    note(rays, n, true);
    inner_.occludedCoherent(rays, blocked, n);
  }
  std::string_view name() const override { return inner_.name(); }

  // (origin, direction, tMax, occlusion, call size) of every ray, sorted.
  using Entry = std::tuple<float, float, float, float, float, float, float, bool, size_t>;
  std::vector<Entry> sorted() const {
    std::vector<Entry> out = entries_;
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  void note(const Ray* rays, size_t n, bool occlusion) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < n; ++i)
      entries_.emplace_back(rays[i].o.x, rays[i].o.y, rays[i].o.z, rays[i].d.x, rays[i].d.y,
                            rays[i].d.z, rays[i].tMax, occlusion, n);
  }
  const Accelerator& inner_;
  mutable std::mutex mutex_;
  mutable std::vector<Entry> entries_;
};

TEST(IntersectionShare, TheReplayTracesExactlyTheRendersQueries) {
  // A mirror sphere and a matte one over a plane under a point light: camera batches, shadow
  // rays and reflection rays.
  Scene s = test::sceneFromText(R"({"render": {"width": 24, "height": 16, "spp": 4},
    "camera": {"eye": [0,1,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}, "mirror": {"type": "mirror"}},
    "lights": [{"type": "point", "position": [2,4,3]}],
    "objects": [{"type": "sphere", "center": [-0.6,0,0], "radius": 0.5, "material": "mirror"},
                {"type": "sphere", "center": [0.6,0,0], "radius": 0.5, "material": "m"},
                {"type": "plane", "point": [0,-0.5,0], "normal": [0,1,0], "material": "m"}]})");
  const auto embree = makeAccelerator(AccelKind::Embree, s);
  RenderOptions opt;
  opt.threads = 1;
  opt.progress = false;
  // What the render asks, logged, and what the recorder keeps of the same render (stride 1).
  const QueryLog rendered(*embree);
  RayRecorder recorder(rendered);
  const RenderStats stats = renderScene(s, recorder, opt).stats;
  const std::vector<RecordedRay> recorded = recorder.take();
  // Each pixel's 4 camera rays, at least, went through the backend.
  ASSERT_GE(recorded.size(), size_t(24 * 16 * 4));
  EXPECT_GE(uint64_t(recorded.size()), stats.rays.camera);

  for (const bool asTraced : {true, false}) {
    SCOPED_TRACE(asTraced ? "as traced" : "one by one");
    const QueryLog replayed(*embree);
    replaySeconds(replayed, recorded, 1, asTraced, 2);
    std::vector<QueryLog::Entry> expected = rendered.sorted(), got = replayed.sorted();
    if (!asTraced)  // one ray per call
      for (auto& e : expected) std::get<8>(e) = 1;
    // Two passes: every query twice.
    std::vector<QueryLog::Entry> twice;
    for (const auto& e : expected) twice.insert(twice.end(), {e, e});
    EXPECT_EQ(got.size(), twice.size());
    EXPECT_TRUE(got == twice);
  }
}

}  // namespace
}  // namespace glint
