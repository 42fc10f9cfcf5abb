#pragma once
// The interior list for nested dielectrics (glass inside water): the dielectric objects a ray
// is inside, innermost last, each with its material. Entering an object's surface (decided by
// the geometric normal) pushes it; leaving removes it wherever it sits, so overlapping or
// coincident boundaries resolve without priorities. The medium the ray travels
// in is the innermost entry's, or the outside world (index of refraction 1) when empty.
// Objects are told apart by a key from the hit (instance and geometry id), not by material, so
// two overlapping spheres of the same glass behave as one piece.
#include <cstdint>

#include "geometry/hit.h"

namespace glint {

inline uint64_t objectKey(const Hit& hit) { return (uint64_t(hit.instId) << 32) | hit.geomId; }

class MediumStack {
 public:
  static constexpr int kCapacity = 8;  // deeper nesting than this is ignored (outermost kept)

  bool empty() const { return size_ == 0; }
  uint32_t innermostMaterial() const { return entries_[size_ - 1].materialId; }
  MediumStack entered(uint64_t objectKey, uint32_t materialId) const {
    MediumStack s = *this;
    if (s.size_ < kCapacity) s.entries_[s.size_++] = {objectKey, materialId};
    return s;
  }
  MediumStack left(uint64_t objectKey) const {
    MediumStack s;
    for (int i = 0; i < size_; ++i)
      if (entries_[i].objectKey != objectKey) s.entries_[s.size_++] = entries_[i];
    return s;
  }

 private:
  struct Entry {
    uint64_t objectKey;
    uint32_t materialId;
  };
  Entry entries_[kCapacity] = {};
  int size_ = 0;
};

}  // namespace glint
