#pragma once
// Whether a primitive's *surface* meets an axis-aligned cell (seed 002 §9.2.2: only cells that
// hold a part of some surface need a list; a cell inside a solid or outside everything tells a
// ray only that it hits nothing there). The octree and the uniform grid list a primitive in a
// cell by these tests instead of by its box. Exact for the shapes whose surface is simple
// (sphere, triangle, parallelogram, disk), by the box for the rest (CSG solids, instances, and
// anything that moves, boxed over the shutter).
#include <cstdint>

#include "accel/primitives.h"
#include "core/bounds.h"
#include "core/vec.h"

namespace glint {

enum class CellContact {
  Apart,    // the surface does not meet the cell
  Surface,  // it does: the primitive goes on the cell's list
  Inside,   // it does not, and the cell lies inside the primitive's solid (a "full" cell)
};

// The contact of primitive `p` of group `groupId` with `cell`, the cell padded first
// (paddedCell) so that no hit the shared intersection routine reports inside the cell is lost.
CellContact surfaceContact(const Scene& scene, uint32_t groupId, const PrimitiveBox& p,
                           const Bounds3f& cell);
// The same for a cell already padded (a build that tests many primitives against one cell pads
// it once).
CellContact paddedSurfaceContact(const Scene& scene, uint32_t groupId, const PrimitiveBox& p,
                                 const Bounds3f& padded);

// `cell` grown on every side by 10⁻⁴ of its largest side and 2⁻¹⁸ of its largest coordinate.
Bounds3f paddedCell(const Bounds3f& cell);

// The exact tests, on the box as given (no padding), computed in double.
// The sphere's surface meets the box iff the box's nearest point is within r of the centre and
// its farthest corner at least r away; Inside when that corner is nearer than r.
CellContact sphereContact(const Vec3f& center, float radius, const Bounds3f& box);
// Separating axes (Akenine-Möller 2001): the box's 3 normals, the triangle's normal and the 9
// cross products of its edges with the box's axes.
bool triangleMeetsBox(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Bounds3f& box);
// The parallelogram corner + α·edge1 + β·edge2 (α, β ∈ [0, 1]), by the same axes for its two
// edge directions.
bool parallelogramMeetsBox(const Vec3f& corner, const Vec3f& edge1, const Vec3f& edge2,
                           const Bounds3f& box);
// The disk meets the box iff its plane cuts the box and the polygon it cuts is within `radius`
// of the centre.
bool diskMeetsBox(const Vec3f& center, const Vec3f& normal, float radius, const Bounds3f& box);

}  // namespace glint
