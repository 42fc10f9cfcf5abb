#pragma once
// Triangle mesh in the layout Embree shares without copying: packed float3 positions (with one
// float of tail padding, which Embree's 16-byte loads need) and uint32 index triples.
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "core/vec.h"

namespace glint {

struct TriangleMesh {
  std::vector<Vec3f> positions;   // capacity ≥ size + 1: see padForEmbree()
  std::vector<uint32_t> indices;  // 3 per triangle

  size_t triangleCount() const { return indices.size() / 3; }
  Vec3f vertex(uint32_t tri, int corner) const {
    return positions[indices[3 * tri + static_cast<uint32_t>(corner)]];
  }
  Bounds3f bounds() const {
    Bounds3f b;
    for (const auto& p : positions) b.extend(p);
    return b;
  }
  // Embree reads vertex buffers with 16-byte loads, so the last vertex needs 4 spare bytes.
  void padForEmbree() { positions.reserve(positions.size() + 1); }
};

}  // namespace glint
