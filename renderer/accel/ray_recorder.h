#pragma once
// Records the queries a render makes, so `glint bench` can replay exactly those rays through
// Embree alone and measure how close the whole renderer comes to bare traversal speed (the
// Embree-limit ratio). A decorator over any backend; it costs a vector push per ray, so the
// recorded render is never the timed one. With a stride k it keeps one query in k of each
// thread (a coherent batch is one query, kept whole), picked by a hash of the query's number
// so that no periodic pattern of the render's queries (a camera batch, then its shadow batch,
// ...) aliases with the stride: a fixed subset with the render's mix of ray kinds, in bounded
// memory, that can be replayed one ray at a time or as it was traced.
#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "accel/accelerator.h"
#include "core/hash.h"

namespace glint {

struct RecordedRay {
  Ray ray;
  bool occlusion = false;  // an occluded() query rather than intersect()
  // On a query's first ray, the rays it traced together (1, or a coherent batch's size); 0 on
  // a batch's other rays.
  uint32_t query = 1;
};

class RayRecorder final : public Accelerator {
 public:
  explicit RayRecorder(const Accelerator& inner, uint64_t stride = 1)
      : inner_(inner), stride_(stride) {}

  Hit intersect(const Ray& ray) const override {
    record(ray, false);
    return inner_.intersect(ray);
  }
  bool occluded(const Ray& ray) const override {
    record(ray, true);
    return inner_.occluded(ray);
  }
  void intersectCoherent(const Ray* rays, Hit* hits, size_t n) const override {
    record(rays, n, false);
    inner_.intersectCoherent(rays, hits, n);
  }
  void occludedCoherent(const Ray* rays, bool* blocked, size_t n) const override {
    record(rays, n, true);
    inner_.occludedCoherent(rays, blocked, n);
  }
  std::string_view name() const override { return inner_.name(); }

  // The recorded queries, in no particular order (the threads' lists concatenated), each
  // batch's rays together.
  std::vector<RecordedRay> take();

 private:
  struct PerThread {
    std::vector<RecordedRay> rays;
    uint64_t seen = 0;
  };
  void record(const Ray& ray, bool occlusion) const { record(&ray, 1, occlusion); }
  void record(const Ray* rays, size_t n, bool occlusion) const {
    PerThread& t = local_.local();
    if (mix64(t.seen++) % stride_ != 0) return;
    for (size_t i = 0; i < n; ++i)
      t.rays.push_back({rays[i], occlusion, i == 0 ? static_cast<uint32_t>(n) : 0u});
  }

  const Accelerator& inner_;
  uint64_t stride_;
  mutable tbb::enumerable_thread_specific<PerThread> local_;
};

}  // namespace glint
