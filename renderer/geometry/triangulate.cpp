#include "geometry/triangulate.h"

#include <cmath>

namespace glint {

namespace {

float cross2(Vec2f a, Vec2f b, Vec2f c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool insideTriangle(Vec2f p, Vec2f a, Vec2f b, Vec2f c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

}  // namespace

bool triangulatePolygon(const std::vector<Vec3f>& vertices, std::vector<uint32_t>& triangles) {
  const size_t n = vertices.size();
  if (n < 3) return false;
  // Newell's normal is robust for non-planar and concave polygons alike.
  Vec3f normal;
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& a = vertices[i];
    const Vec3f& b = vertices[(i + 1) % n];
    normal +=
        Vec3f{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  const Vec3f an = abs(normal);
  if (maxComponent(an) == 0) return false;
  const int drop = an.x > an.y ? (an.x > an.z ? 0 : 2) : (an.y > an.z ? 1 : 2);
  const int ax = (drop + 1) % 3, ay = (drop + 2) % 3;
  const float sign = normal[drop] > 0 ? 1.0f : -1.0f;  // make the 2D polygon counter-clockwise
  std::vector<Vec2f> p(n);
  for (size_t i = 0; i < n; ++i) p[i] = {vertices[i][ax], sign * vertices[i][ay]};

  std::vector<uint32_t> ring(n);
  for (size_t i = 0; i < n; ++i) ring[i] = static_cast<uint32_t>(i);
  triangles.clear();
  while (ring.size() > 3) {
    bool clipped = false;
    for (size_t i = 0; i < ring.size() && !clipped; ++i) {
      const uint32_t ia = ring[(i + ring.size() - 1) % ring.size()], ib = ring[i],
                     ic = ring[(i + 1) % ring.size()];
      if (cross2(p[ia], p[ib], p[ic]) <= 0) continue;  // reflex or collinear: not an ear
      bool empty = true;
      for (uint32_t j : ring)
        if (j != ia && j != ib && j != ic && insideTriangle(p[j], p[ia], p[ib], p[ic])) {
          empty = false;
          break;
        }
      if (!empty) continue;
      triangles.insert(triangles.end(), {ia, ib, ic});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (cross2(p[ring[0]], p[ring[1]], p[ring[2]]) <= 0) return false;
  triangles.insert(triangles.end(), {ring[0], ring[1], ring[2]});
  return true;
}

}  // namespace glint
