#pragma once
// Polygon triangulation by ear clipping in the polygon's dominant plane; concave polygons come
// out right. Returns false when the polygon is degenerate or self-intersecting.
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace glint {

bool triangulatePolygon(const std::vector<Vec3f>& vertices, std::vector<uint32_t>& triangles);

}  // namespace glint
