#pragma once
// Ray–sphere and ray–quad tests for a packet of rays at once, in the structure-of-arrays layout
// Embree hands user geometry when it traces a coherent stream (16 rays a packet on an AVX-512
// machine). Each lane gives the same bits as intersectSphere / intersectQuad: the same
// operations in the same order, in vector registers (square root and division are correctly
// rounded in both, and no FMA is formed: -ffp-contract=off), so a render does not depend on
// which rays shared a packet.
#include <cstdint>

#include "geometry/shapes.h"

namespace glint {

// Lane l of a packet: origin (o[0][l], o[1][l], o[2][l]), direction likewise, its interval
// (tMin[l], tMax[l]); valid[l] zero for a lane to ignore (Embree's mask).
struct RayLanes {
  const float* o[3];
  const float* d[3];
  const float* tMin;
  const float* tMax;
  const int* valid;
};

// The largest packet intersectLanes takes.
inline constexpr int kMaxLanes = 16;

// Per lane of a hit: t, and (u, v) as the scalar test gives them (0 for a sphere).
struct LaneHits {
  float t[kMaxLanes], u[kMaxLanes], v[kMaxLanes];
};

// Tests lanes [0, n) (n ≤ kMaxLanes) against the shape: bit l of the result is set when lane
// l is valid and hits it, and then hits holds lane l's t (and u, v) as the scalar test gives
// them; other lanes' entries are unspecified. `width` picks the vector width (4: SSE2, 8: AVX2,
// 16: AVX-512F) for tests; 0 takes the widest this CPU runs.
uint32_t intersectLanes(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits,
                        int width = 0);
uint32_t intersectLanes(const Quad& q, const RayLanes& rays, int n, LaneHits& hits, int width = 0);
// Whether this CPU runs `width` (4, 8 or 16).
bool laneWidthSupported(int width);

}  // namespace glint
