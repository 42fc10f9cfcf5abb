#pragma once
// The interior list for nested dielectrics (glass inside water): the dielectric objects a ray
// is inside, innermost last, each with its material. Entering an object's surface (decided by
// the geometric normal) pushes it; leaving removes it wherever it sits, so overlapping or
// coincident boundaries resolve without priorities. The medium the ray travels
// in is the innermost entry's, or the outside world (index of refraction 1) when empty.
// Objects are told apart by a key from the hit (instance and geometry id), not by material, so
// two overlapping spheres of the same glass behave as one piece.
#include <algorithm>
#include <cstdint>

#include "geometry/hit.h"

namespace glint {

inline uint64_t objectKey(const Hit& hit) { return (uint64_t(hit.instId) << 32) | hit.geomId; }

class MediumStack {
 public:
  static constexpr int kCapacity = 8;  // deeper nesting than this is ignored (outermost kept)

  // Becomes a copy of o, writing only the entries in use: every spawned ray carries a copy
  // (Generation::add), and most stacks are empty or nearly so. Assigned whole, the stack was
  // 136 bytes written per ray, and in a chain of mirror bounces each copy landed in a buffer
  // that had left the cache.
  void assign(const MediumStack& o) {
    size_ = o.size_;
    std::copy_n(o.entries_, o.size_, entries_);
  }

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
  int size_ = 0;  // first: a stack that is empty is read and written in its first bytes
  Entry entries_[kCapacity] = {};  // [0, size_) in use; the rest is never read
};

}  // namespace glint
