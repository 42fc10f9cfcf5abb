#pragma once
// Hit: the only thing intersection backends must agree on. Embree's conventions:
// p = (1-u-v)·p0 + u·p1 + v·p2 for triangles; (u, v) are the shape's own parameters otherwise.
#include <cstdint>

#include "core/vec.h"

namespace glint {

inline constexpr uint32_t kInvalidId = 0xffffffffu;

struct Hit {
  float t = kInfinity, u = 0, v = 0;
  uint32_t geomId = kInvalidId, primId = kInvalidId, instId = kInvalidId;
  explicit operator bool() const { return geomId != kInvalidId; }
};

}  // namespace glint
