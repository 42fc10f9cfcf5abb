#pragma once
// The per-instruction-set entry points of intersectLanes (shape_lanes.cpp dispatches): each
// tests lanes [0, n) of a packet, n a multiple of its width, and is defined in a file compiled
// for that instruction set. Call one only where the CPU has it.
#include <cstdint>

#include "geometry/shape_lanes.h"

namespace glint::shape_lanes {

uint32_t sse2(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits);  // width 4
uint32_t sse2(const Quad& q, const RayLanes& rays, int n, LaneHits& hits);
uint32_t avx2(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits);  // width 8
uint32_t avx2(const Quad& q, const RayLanes& rays, int n, LaneHits& hits);
uint32_t avx512(const Sphere& s, const RayLanes& rays, int n, LaneHits& hits);  // width 16
uint32_t avx512(const Quad& q, const RayLanes& rays, int n, LaneHits& hits);

}  // namespace glint::shape_lanes
