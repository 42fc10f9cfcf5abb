#pragma once
// The per-instruction-set entry points of intersectSphereLanes (sphere_lanes.cpp dispatches):
// each tests lanes [0, n) of a packet, n a multiple of its width, and is defined in a file
// compiled for that instruction set. Call one only where the CPU has it.
#include <cstdint>

#include "geometry/sphere_lanes.h"

namespace glint::sphere_lanes {

uint32_t sse2(const Sphere& s, const RayLanes& rays, int n, float* tHit);    // width 4
uint32_t avx2(const Sphere& s, const RayLanes& rays, int n, float* tHit);    // width 8
uint32_t avx512(const Sphere& s, const RayLanes& rays, int n, float* tHit);  // width 16

}  // namespace glint::sphere_lanes
