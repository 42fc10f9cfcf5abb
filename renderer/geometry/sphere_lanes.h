#pragma once
// Ray–sphere tests for a packet of rays at once, in the structure-of-arrays layout Embree hands
// user geometry when it traces a coherent stream (16 rays a packet on an AVX-512 machine). Each
// lane gives the same bits as intersectSphere: the same operations in the same order, in
// vector registers (sqrt and division are correctly rounded in both, and no FMA is formed:
// -ffp-contract=off), so a render does not depend on which rays shared a packet.
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

// The largest packet intersectSphereLanes takes.
inline constexpr int kMaxSphereLanes = 16;

// Tests lanes [0, n) (n ≤ kMaxSphereLanes) against s: bit l of the result is set when lane l
// is valid and hits s, and then tHit[l] = intersectSphere(s, that ray); other entries of tHit
// are unspecified. `width` picks the vector width (4: SSE2, 8: AVX2, 16: AVX-512F) for tests;
// 0 takes the widest this CPU runs.
uint32_t intersectSphereLanes(const Sphere& s, const RayLanes& rays, int n, float* tHit,
                              int width = 0);
// Whether this CPU runs `width` (4, 8 or 16).
bool sphereLaneWidthSupported(int width);

}  // namespace glint
