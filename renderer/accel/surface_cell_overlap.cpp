#include "accel/surface_cell_overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace glint {

namespace {

using D3 = std::array<double, 3>;

D3 asDouble(const Vec3f& v) { return {v.x, v.y, v.z}; }
D3 operator-(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 operator+(const D3& a, const D3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
D3 operator*(double s, const D3& a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Whether `axis` separates the points `v` (relative to the box's centre) from a box of half
// extents `h` centred at the origin. A zero axis (a degenerate edge or normal) separates nothing.
template <size_t N>
bool separates(const D3& axis, const std::array<D3, N>& v, const D3& h) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const D3& p : v) {
    const double s = dot(axis, p);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  const double r =
      h[0] * std::fabs(axis[0]) + h[1] * std::fabs(axis[1]) + h[2] * std::fabs(axis[2]);
  return lo > r || hi < -r;
}

// A flat convex polygon with corners `v` against the box: separating axes are the box's
// normals, the polygon's normal and the cross products of its edge directions with the box's
// axes (for a polygon, unlike a solid, no more are needed).
template <size_t N, size_t E>
bool flatPolygonMeetsBox(std::array<D3, N> v, const std::array<D3, E>& edges, const Bounds3f& box) {
  const D3 lo = asDouble(box.lo), hi = asDouble(box.hi);
  const D3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  for (D3& p : v) p = p - c;
  for (int a = 0; a < 3; ++a) {
    D3 axis{0, 0, 0};
    axis[size_t(a)] = 1;
    if (separates(axis, v, h)) return false;
  }
  if (separates(cross(edges[0], edges[E - 1]), v, h)) return false;
  for (const D3& e : edges)
    for (int a = 0; a < 3; ++a) {
      D3 axis{0, 0, 0};
      axis[size_t(a)] = 1;
      if (separates(cross(e, axis), v, h)) return false;
    }
  return true;
}

// Distance from the origin to the segment [a, b] of the plane.
double segmentDistance(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  const double s = len2 > 0 ? std::clamp(-(a[0] * dx + a[1] * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(a[0] + s * dx, a[1] + s * dy);
}

// Distance from the origin to the convex hull of `n` points of the plane (Andrew's monotone
// chain; 0 inside it).
double hullDistance(std::array<std::array<double, 2>, 24>& p, size_t n) {
  std::sort(p.begin(), p.begin() + std::ptrdiff_t(n));
  const auto turn = [](const auto& o, const auto& a, const auto& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::array<std::array<double, 2>, 48> hull;
  size_t k = 0;
  for (size_t i = 0; i < n; ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = n - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  if (k > 1) --k;  // the last point repeats the first
  if (k == 1) return std::hypot(hull[0][0], hull[0][1]);
  bool inside = k >= 3;
  double nearest = std::numeric_limits<double>::infinity();
  const std::array<double, 2> origin{0, 0};
  for (size_t i = 0; i < k; ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % k];
    inside = inside && turn(a, b, origin) >= 0;
    nearest = std::min(nearest, segmentDistance(a, b));
  }
  return inside ? 0 : nearest;
}

bool overlaps(const Bounds3f& a, const Bounds3f& b) {
  for (int i = 0; i < 3; ++i)
    if (a.lo[i] > b.hi[i] || a.hi[i] < b.lo[i]) return false;
  return true;
}

}  // namespace

Bounds3f paddedCell(const Bounds3f& cell) {
  // A hit the shared routines compute lies off the true surface by the rounding of the ray
  // (a few float steps of the coordinates: 2⁻¹⁸ of the largest is 32 steps of it), and the
  // structures place a hit in a cell by float plane crossings that may put it a hair across a
  // face (10⁻⁴ of the cell, as the box-based lists were padded): a surface within this pad of
  // the cell is listed, so a hit reported just outside the cell is still found there.
  float side = 0, reach = 0;
  for (int a = 0; a < 3; ++a) {
    side = std::max(side, cell.hi[a] - cell.lo[a]);
    reach = std::max({reach, std::fabs(cell.lo[a]), std::fabs(cell.hi[a])});
  }
  const float pad = 1e-4f * side + 0x1p-18f * reach;
  const Vec3f p{pad, pad, pad};
  return {cell.lo - p, cell.hi + p};
}

CellContact sphereContact(const Vec3f& center, float radius, const Bounds3f& box) {
  double nearest = 0, farthest = 0;
  for (int a = 0; a < 3; ++a) {
    const double c = center[a], lo = box.lo[a], hi = box.hi[a];
    const double gap = std::max({lo - c, 0.0, c - hi});
    const double far = std::max(std::fabs(c - lo), std::fabs(c - hi));
    nearest += gap * gap;
    farthest += far * far;
  }
  const double r2 = double(radius) * double(radius);
  if (nearest > r2) return CellContact::Apart;
  if (farthest < r2) return CellContact::Inside;
  return CellContact::Surface;
}

bool triangleMeetsBox(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Bounds3f& box) {
  const D3 a = asDouble(p0), b = asDouble(p1), c = asDouble(p2);
  return flatPolygonMeetsBox(std::array<D3, 3>{a, b, c}, std::array<D3, 3>{b - a, c - b, a - c},
                             box);
}

bool parallelogramMeetsBox(const Vec3f& corner, const Vec3f& edge1, const Vec3f& edge2,
                           const Bounds3f& box) {
  const D3 c = asDouble(corner), e1 = asDouble(edge1), e2 = asDouble(edge2);
  return flatPolygonMeetsBox(std::array<D3, 4>{c, c + e1, c + e1 + e2, c + e2},
                             std::array<D3, 2>{e1, e2}, box);
}

bool diskMeetsBox(const Vec3f& center, const Vec3f& normal, float radius, const Bounds3f& box) {
  if (sphereContact(center, radius, box) == CellContact::Apart) return false;
  D3 n = asDouble(normal);
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0)) return true;  // no plane to cut with: keep it
  n = (1 / len) * n;
  // The box's corners relative to the centre, and their heights above the disk's plane.
  const D3 c = asDouble(center);
  std::array<D3, 8> k;
  std::array<double, 8> s;
  for (int i = 0; i < 8; ++i) {
    k[size_t(i)] = asDouble(box.corner(i)) - c;
    s[size_t(i)] = dot(n, k[size_t(i)]);
  }
  // The plane cuts the box in a convex polygon whose corners lie on the box's 12 edges.
  const D3 u0 = std::fabs(n[0]) < 0.9 ? D3{1, 0, 0} : D3{0, 1, 0};
  D3 u = cross(n, u0);
  u = (1 / std::sqrt(dot(u, u))) * u;
  const D3 v = cross(n, u);
  std::array<std::array<double, 2>, 24> points;
  size_t count = 0;
  const auto add = [&](const D3& p) { points[count++] = {dot(p, u), dot(p, v)}; };
  for (int i = 0; i < 8; ++i)
    for (int a = 0; a < 3; ++a) {
      const int j = i | (1 << a);
      if (j == i) continue;
      const double si = s[size_t(i)], sj = s[size_t(j)];
      if ((si > 0 && sj > 0) || (si < 0 && sj < 0)) continue;
      if (si == sj) {  // the edge lies in the plane
        add(k[size_t(i)]);
        add(k[size_t(j)]);
      } else {
        add(k[size_t(i)] + (si / (si - sj)) * (k[size_t(j)] - k[size_t(i)]));
      }
    }
  if (count == 0) return false;
  return hullDistance(points, count) <= radius;
}

CellContact surfaceContact(const Scene& scene, uint32_t groupId, const PrimitiveBox& p,
                           const Bounds3f& cell) {
  return paddedSurfaceContact(scene, groupId, p, paddedCell(cell));
}

CellContact paddedSurfaceContact(const Scene& scene, uint32_t groupId, const PrimitiveBox& p,
                                 const Bounds3f& cell) {
  if (!overlaps(p.box, cell)) return CellContact::Apart;
  const auto meets = [](bool m) { return m ? CellContact::Surface : CellContact::Apart; };
  const Geometry& g = scene.groups[groupId].geometries[p.geom];
  switch (g.kind) {
    case GeomKind::Mesh: {
      const TriangleMesh& m = scene.meshes[g.index];
      if (m.deforming()) return CellContact::Surface;  // its box over the shutter meets the cell
      return meets(
          triangleMeetsBox(m.vertex(p.prim, 0), m.vertex(p.prim, 1), m.vertex(p.prim, 2), cell));
    }
    case GeomKind::Sphere: {
      if (g.index < scene.sphereCenterKeys.size() && !scene.sphereCenterKeys[g.index].empty())
        return CellContact::Surface;
      const Sphere& s = scene.spheres[g.index];
      return sphereContact(s.center, s.radius, cell);
    }
    case GeomKind::Quad: {
      const Quad& q = scene.quads[g.index];
      return meets(parallelogramMeetsBox(q.corner, q.edge1, q.edge2, cell));
    }
    case GeomKind::Disk: {
      const Disk& d = scene.disks[g.index];
      return meets(diskMeetsBox(d.center, d.normal, d.radius, cell));
    }
    case GeomKind::Csg:
    case GeomKind::Instance:
    case GeomKind::Plane:
      break;  // by the box, which meets the cell
  }
  return CellContact::Surface;
}

}  // namespace glint
