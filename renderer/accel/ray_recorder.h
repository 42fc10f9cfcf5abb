#pragma once
// Records the queries a render makes, so `glint bench` can replay exactly those rays through
// Embree alone and measure how close the whole renderer comes to bare traversal speed (the
// Embree-limit ratio). A decorator over any backend; it costs a vector push per ray, so the
// recorded render is never the timed one. With a stride k it keeps every k-th query of each
// thread: a fixed subset with the render's mix of ray kinds, in bounded memory.
#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "accel/accelerator.h"

namespace glint {

struct RecordedRay {
  Ray ray;
  bool occlusion = false;  // an occluded() query rather than intersect()
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
  std::string_view name() const override { return inner_.name(); }

  // The recorded queries, in no particular order (the threads' lists concatenated).
  std::vector<RecordedRay> take();

 private:
  struct PerThread {
    std::vector<RecordedRay> rays;
    uint64_t seen = 0;
  };
  void record(const Ray& ray, bool occlusion) const {
    PerThread& t = local_.local();
    if (t.seen++ % stride_ == 0) t.rays.push_back({ray, occlusion});
  }

  const Accelerator& inner_;
  uint64_t stride_;
  mutable tbb::enumerable_thread_specific<PerThread> local_;
};

}  // namespace glint
