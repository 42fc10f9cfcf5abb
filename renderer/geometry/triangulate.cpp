#include "geometry/triangulate.h"

#include <algorithm>
#include <cmath>

#include "core/bounds.h"

namespace glint {

namespace {

float cross2(Vec2f a, Vec2f b, Vec2f c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool insideTriangle(Vec2f p, Vec2f a, Vec2f b, Vec2f c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

// The polygon's reflex (and collinear) vertices in a uniform grid of about one per cell. A
// vertex inside a candidate ear of a simple polygon means a reflex vertex inside it (Eberly,
// "Triangulation by Ear Clipping"), so an ear is tested against these alone, found through the
// cells its box covers: a convex polygon has none, and a clip changes only its two neighbours.
class ReflexGrid {
 public:
  ReflexGrid(const std::vector<Vec2f>& p, const std::vector<uint32_t>& reflex) : p_(p) {
    for (uint32_t i : reflex) box_.extend(Vec3f{p[i].x, p[i].y, 0});
    cells_ = std::clamp(int(std::ceil(std::sqrt(double(reflex.size())))), 1, 1024);
    const float w = box_.hi.x - box_.lo.x, h = box_.hi.y - box_.lo.y;
    scaleX_ = w > 0 && std::isfinite(w) ? float(cells_) / w : 0;
    scaleY_ = h > 0 && std::isfinite(h) ? float(cells_) / h : 0;
    // Counting sort into the cells: start_[c] .. start_[c + 1] index `members_`.
    start_.assign(size_t(cells_) * size_t(cells_) + 1, 0);
    for (uint32_t i : reflex) ++start_[cellOf(p[i]) + 1];
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    members_.resize(reflex.size());
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (uint32_t i : reflex) members_[fill[cellOf(p[i])]++] = i;
  }

  // Whether a vertex other than ia, ib, ic for which `counts` holds lies in the triangle.
  template <typename Counts>
  bool anyInside(uint32_t ia, uint32_t ib, uint32_t ic, Counts counts) const {
    const Vec2f a = p_[ia], b = p_[ib], c = p_[ic];
    const int x0 = column(std::min({a.x, b.x, c.x})), x1 = column(std::max({a.x, b.x, c.x}));
    const int y0 = row(std::min({a.y, b.y, c.y})), y1 = row(std::max({a.y, b.y, c.y}));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const size_t cell = size_t(y) * size_t(cells_) + size_t(x);
        for (uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
          const uint32_t j = members_[k];
          if (j != ia && j != ib && j != ic && counts(j) && insideTriangle(p_[j], a, b, c))
            return true;
        }
      }
    return false;
  }

 private:
  int column(float x) const { return cellIndex((x - box_.lo.x) * scaleX_); }
  int row(float y) const { return cellIndex((y - box_.lo.y) * scaleY_); }
  // Clamped in float before the conversion, which is undefined for NaN (a grid of no reflex
  // vertices has an empty box: ∞ · 0) and past int's range.
  int cellIndex(float t) const { return t > 0 ? int(std::min(t, float(cells_ - 1))) : 0; }
  size_t cellOf(Vec2f q) const { return size_t(row(q.y)) * size_t(cells_) + size_t(column(q.x)); }

  const std::vector<Vec2f>& p_;
  Bounds3f box_;
  int cells_ = 1;
  float scaleX_ = 0, scaleY_ = 0;
  std::vector<uint32_t> start_, members_;
};

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

  // The ring as a doubly linked list; ears are clipped walking forwards from vertex 0, each
  // clip moving past the ear's successor (as earcut does), so that ears stay small and local
  // instead of fanning out from one vertex across the polygon.
  std::vector<uint32_t> prev(n), next(n);
  for (size_t i = 0; i < n; ++i) {
    prev[i] = uint32_t((i + n - 1) % n);
    next[i] = uint32_t((i + 1) % n);
  }
  const auto convex = [&](uint32_t i) { return cross2(p[prev[i]], p[i], p[next[i]]) > 0; };
  std::vector<char> reflex(n);
  std::vector<uint32_t> reflexList;
  for (uint32_t i = 0; i < n; ++i)
    if (!convex(i)) {
      reflex[i] = 1;
      reflexList.push_back(i);
    }
  const ReflexGrid grid(p, reflexList);
  triangles.clear();
  triangles.reserve(3 * (n - 2));
  uint32_t at = 0;
  size_t remaining = n, sinceClip = 0;
  while (remaining > 3) {
    const uint32_t ia = prev[at], ic = next[at];
    if (reflex[at] || grid.anyInside(ia, at, ic, [&](uint32_t j) { return reflex[j] != 0; })) {
      at = ic;
      if (++sinceClip >= remaining) return false;  // a whole turn without an ear
      continue;
    }
    triangles.insert(triangles.end(), {ia, at, ic});
    next[ia] = ic;
    prev[ic] = ia;
    --remaining;
    sinceClip = 0;
    // Clipping only opens the neighbours' angles: a reflex one may turn convex, never back.
    for (uint32_t j : {ia, ic})
      if (reflex[j] && convex(j)) reflex[j] = 0;
    at = next[ic];
  }
  // The last three, from the lowest index, as the ring lists them.
  const uint32_t first = std::min({at, next[at], prev[at]});
  const uint32_t second = next[first], third = next[second];
  if (cross2(p[first], p[second], p[third]) <= 0) return false;
  triangles.insert(triangles.end(), {first, second, third});
  return true;
}

}  // namespace glint
