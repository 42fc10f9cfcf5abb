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
#include <vector>

#include "geometry/hit.h"
#include "materials/material.h"

namespace glint {

inline uint64_t objectKey(const Hit& hit) { return (uint64_t(hit.instId) << 32) | hit.geomId; }

class MediumStack {
 public:
  static constexpr int kCapacity = 8;  // deeper nesting than this is ignored (outermost kept)

  // Becomes a copy of o, writing only the entries in use: every spawned ray carries a copy
  // (Generation::add), most stacks are empty or nearly so, and 136 bytes per ray missed the
  // cache in long chains of mirror bounces.
  void assign(const MediumStack& o) {
    size_ = o.size_;
    std::copy_n(o.entries_, o.size_, entries_);
  }

  bool empty() const { return size_ == 0; }
  uint32_t innermostMaterial() const { return entries_[size_ - 1].materialId; }
  // The material object `objectKey` was entered with, or `otherwise` when it is not in the list.
  // (A CSG solid's surfaces may name different materials: the one it was entered by fills it.)
  uint32_t materialInside(uint64_t objectKey, uint32_t otherwise) const {
    for (int i = size_; i-- > 0;)
      if (entries_[i].objectKey == objectKey) return entries_[i].materialId;
    return otherwise;
  }
  // This list with the object entered, or left, written into `out` (not returned: a returned
  // stack was zeroed whole before it was filled, a 150-byte store per dielectric crossing).
  void enterInto(MediumStack& out, uint64_t objectKey, uint32_t materialId) const {
    out.assign(*this);
    if (out.size_ < kCapacity) out.entries_[out.size_++] = {objectKey, materialId};
  }
  void leaveInto(MediumStack& out, uint64_t objectKey) const {
    out.size_ = 0;
    for (int i = 0; i < size_; ++i)
      if (entries_[i].objectKey != objectKey) out.entries_[out.size_++] = entries_[i];
  }

 private:
  struct Entry {
    uint64_t objectKey;
    uint32_t materialId;
  };
  int size_ = 0;  // first: a stack that is empty is read and written in its first bytes
  // [0, size_) in use; the rest is never read, so it is left uninitialised: zeroing it cost a
  // 128-byte store per stack made (every dielectric crossing makes one).
  Entry entries_[kCapacity];
};

// A ray meeting a dielectric's surface at a hit: which way it crosses, and the indices of
// refraction on its side and across, from the interior list. Entering or leaving is decided by
// the geometric normal ng and the ray's direction d, never the shading normal. Entering object
// O: η_i is the current medium's, η_t O's. Leaving O: η_i is O's (the material O was entered
// with, as Beer's law inside used), η_t that of the medium that remains once O is removed (1, the
// outside world, when none).
struct Crossing {
  bool entering = false;
  float etaI = 1, etaT = 1;
  MediumStack across;  // the interior list on the far side
};

inline float iorOf(const MediumStack& media, const std::vector<Material>& materials) {
  return media.empty() ? 1.0f : materials[media.innermostMaterial()].dielectric.ior;
}

[[gnu::always_inline]] inline Crossing crossingAt(const MediumStack& media, const Hit& hit,
                                                  uint32_t materialId, const Vec3f& d,
                                                  const Vec3f& ng,
                                                  const std::vector<Material>& materials) {
  const uint64_t key = objectKey(hit);
  Crossing c;
  c.entering = dot(d, ng) < 0;
  const float ior =
      materials[c.entering ? materialId : media.materialInside(key, materialId)].dielectric.ior;
  if (c.entering)
    media.enterInto(c.across, key, materialId);
  else
    media.leaveInto(c.across, key);
  c.etaI = c.entering ? iorOf(media, materials) : ior;
  c.etaT = c.entering ? ior : iorOf(c.across, materials);
  return c;
}

}  // namespace glint
