#include "accel/ray_recorder.h"

namespace glint {

std::vector<RecordedRay> RayRecorder::take() {
  std::vector<RecordedRay> all;
  for (PerThread& t : local_) {
    all.insert(all.end(), t.rays.begin(), t.rays.end());
    t = {};
  }
  return all;
}

}  // namespace glint
