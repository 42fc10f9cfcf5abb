#include "accel/visibility_sets.h"

#include <algorithm>
#include <numbers>

namespace glint {

namespace {

double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
Vec3d unit(const Vec3d& a) { return a * (1 / length(a)); }
double component(const Vec3d& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
double angleBetween(const Vec3d& a, const Vec3d& b) {  // unit vectors
  return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
}

constexpr double kRightAngle = std::numbers::pi / 2;

void boxAround(Shell& s) {
  s.lo = s.hi = s.vertices.front();
  for (const Vec3d& v : s.vertices) {
    s.lo = {std::min(s.lo.x, v.x), std::min(s.lo.y, v.y), std::min(s.lo.z, v.z)};
    s.hi = {std::max(s.hi.x, v.x), std::max(s.hi.y, v.y), std::max(s.hi.z, v.z)};
  }
}

std::vector<Vec3d> corners(const Vec3d& lo, const Vec3d& hi) {
  std::vector<Vec3d> c;
  for (int k = 0; k < 8; ++k)
    c.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  return c;
}

// The largest gap between the two boxes along an axis (≤ 0 when they are not apart).
double boxGap(const Shell& a, const Shell& b) {
  double gap = -1;
  for (int k = 0; k < 3; ++k) {
    gap = std::max(gap, component(b.lo, k) - component(a.hi, k));
    gap = std::max(gap, component(a.lo, k) - component(b.hi, k));
  }
  return gap;
}

// The convex hull of 2-D points, counter-clockwise, collinear points left out (Andrew's
// monotone chain).
std::vector<size_t> hull2d(const std::vector<std::pair<double, double>>& p) {
  std::vector<size_t> order(p.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  const auto turn = [&](size_t o, size_t a, size_t b) {
    return (p[a].first - p[o].first) * (p[b].second - p[o].second) -
           (p[a].second - p[o].second) * (p[b].first - p[o].first);
  };
  std::vector<size_t> h(2 * order.size());
  size_t k = 0;
  for (size_t i : order) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], i) <= 0) --k;
    h[k++] = i;
  }
  for (size_t j = order.size() - 1, t = k + 1; j-- > 0;) {
    const size_t i = order[j];
    while (k >= t && turn(h[k - 2], h[k - 1], i) <= 0) --k;
    h[k++] = i;
  }
  h.resize(k > 1 ? k - 1 : k);
  return h;
}

VisibilitySet spherePair(const Shell& from, const Shell& to, double pad) {
  VisibilitySet set;
  const Vec3d d = to.center - from.center;
  const double distance = length(d), reach = from.radius + to.radius + 2 * pad;
  set.everywhere = !(distance > reach);
  if (set.everywhere) return set;
  set.axis = d * (1 / distance);
  set.halfAngle = std::asin(reach / distance) + kAnglePad;
  set.everywhere = set.halfAngle >= kRightAngle;
  return set;
}

}  // namespace

Shell Shell::ofSphere(const Vec3f& center, float radius) {
  Shell s;
  s.sphere = true;
  s.center = toDouble(center);
  s.radius = radius;
  const Vec3d r{s.radius, s.radius, s.radius};
  s.vertices = corners(s.center - r, s.center + r);
  boxAround(s);
  return s;
}

Shell Shell::ofBox(const Bounds3f& box) {
  Shell s;
  s.vertices = corners(toDouble(box.lo), toDouble(box.hi));
  boxAround(s);
  return s;
}

Shell Shell::ofPolygon(const std::vector<Vec3f>& vertices) {
  Shell s;
  for (const Vec3f& v : vertices) s.vertices.push_back(toDouble(v));
  boxAround(s);
  return s;
}

bool Shell::holds(const Vec3f& p, double pad) const {
  const Vec3d q = toDouble(p);
  if (sphere) return length(q - center) <= radius + pad;  // false for NaN
  return q.x >= lo.x - pad && q.x <= hi.x + pad && q.y >= lo.y - pad && q.y <= hi.y + pad &&
         q.z >= lo.z - pad && q.z <= hi.z + pad;
}

VisibilitySet visibilitySet(const Shell& from, const Shell& to, double pad) {
  if (from.sphere && to.sphere) return spherePair(from, to, pad);
  VisibilitySet set;
  // Every point of to − from is at least `gap` from 0; growing both shells by `pad` (within a
  // cube of half-side pad) moves a difference by at most 2√3·pad, which turns its direction by
  // at most asin(2√3·pad / gap).
  const double gap = boxGap(from, to), shift = 2 * std::sqrt(3.0) * pad;
  if (!(gap > 2 * shift)) {
    set.everywhere = true;
    return set;
  }
  set.pad = std::asin(shift / gap) + kAnglePad;
  std::vector<Vec3d> g;
  Vec3d sum;
  for (const Vec3d& b : to.vertices)
    for (const Vec3d& a : from.vertices) {
      g.push_back(unit(b - a));
      sum = sum + g.back();
    }
  set.axis = unit(sum);
  // The sum's direction is a positive combination of the generators, so it lies inside their
  // hull and every generator is within 90° of it: the gnomonic projection onto the plane
  // tangent at the axis keeps the hull a convex polygon.
  const Vec3d e1 =
      unit(cross(set.axis, std::fabs(set.axis.x) < 0.6 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0}));
  const Vec3d e2 = cross(set.axis, e1);
  std::vector<std::pair<double, double>> flat;
  for (const Vec3d& v : g) {
    const double h = dot(v, set.axis);
    if (!(h > 1e-9)) {
      set.everywhere = true;
      return set;
    }
    flat.emplace_back(dot(v, e1) / h, dot(v, e2) / h);
  }
  const std::vector<size_t> hull = hull2d(flat);
  for (size_t i : hull) set.generators.push_back(g[i]);
  double spread = 0;
  for (const Vec3d& v : set.generators) spread = std::max(spread, angleBetween(v, set.axis));
  set.halfAngle = spread + set.pad;
  if (set.halfAngle >= kRightAngle) {
    set.everywhere = true;
    return set;
  }
  // The planes through 0 and each hull edge, turned towards the hull's inside. A hull of fewer
  // than three points is flat (a polygon seen edge-on): the cap and the class's planes bound it.
  if (hull.size() >= 3) {
    Vec3d inside;
    for (const Vec3d& v : set.generators) inside = inside + v;
    for (size_t i = 0; i < hull.size(); ++i) {
      const Vec3d n = cross(g[hull[i]], g[hull[(i + 1) % hull.size()]]);
      const double len = length(n), side = dot(n, inside);
      if (!(len > 1e-12) || std::fabs(side) < 1e-12 * len * length(inside)) continue;
      set.faces.push_back(n * ((side > 0 ? 1 : -1) / len));
    }
  }
  return set;
}

double shellDistance(const Shell& from, const Shell& to, double pad) {
  double d;
  if (from.sphere && to.sphere) {
    d = length(to.center - from.center) - from.radius - to.radius - 2 * pad;
  } else {
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const double gap = std::max(component(to.lo, k) - component(from.hi, k),
                                  component(from.lo, k) - component(to.hi, k));
      if (gap > 0) sum += gap * gap;
    }
    d = std::sqrt(sum) - 2 * std::sqrt(3.0) * pad;
  }
  return d > 0 ? d : 0;
}

namespace {

// A block of a face: its corners (unit, in order around it), its centre and the angle from the
// centre to its farthest corner (a cap under 90° is convex and holds the hull of its points).
struct Block {
  Vec3d corner[4];
  Vec3d center;
  double spread = 0;
  Block(int face, double u0, double u1, double v0, double v1) {
    const int a = face / 2;
    const double s = face % 2 ? -1 : 1;
    const auto direction = [&](double u, double v) {
      double c[3];
      c[a] = s;
      c[(a + 1) % 3] = u;
      c[(a + 2) % 3] = v;
      return unit(Vec3d{c[0], c[1], c[2]});
    };
    corner[0] = direction(u0, v0);
    corner[1] = direction(u1, v0);
    corner[2] = direction(u1, v1);
    corner[3] = direction(u0, v1);
    center = direction(0.5 * (u0 + u1), 0.5 * (v0 + v1));
    for (const Vec3d& c : corner) spread = std::max(spread, angleBetween(center, c));
  }
};

}  // namespace

bool DirectionClasses::inside(const VisibilitySet& set, int face, double u0, double u1, double v0,
                              double v1) const {
  if (set.everywhere) return true;
  const Block b(face, u0, u1, v0, v1);
  // A cap holds the block's cap; a hull's planes hold its corners (and so the block: both are
  // convex).
  if (set.generators.empty()) return angleBetween(set.axis, b.center) + b.spread <= set.halfAngle;
  if (set.faces.size() < 3) return false;
  for (const Vec3d& n : set.faces)
    for (const Vec3d& c : b.corner)
      if (dot(n, c) < 0) return false;
  return true;
}

bool DirectionClasses::mayMeet(const VisibilitySet& set, int face, double u0, double u1, double v0,
                               double v1) const {
  if (set.everywhere) return true;
  const Block b(face, u0, u1, v0, v1);
  const Vec3d(&corner)[4] = b.corner;
  const Vec3d& center = b.center;
  if (angleBetween(set.axis, center) > set.halfAngle + b.spread) return false;
  // The block is the cone of its corners, inside each plane through two neighbouring corners.
  const double sinPad = std::sin(set.pad);
  for (int k = 0; k < 4; ++k) {
    Vec3d m = cross(corner[k], corner[(k + 1) % 4]);
    m = m * ((dot(m, center) > 0 ? 1 : -1) / length(m));
    if (set.generators.empty()) {
      if (dot(m, set.axis) < -std::sin(set.halfAngle)) return false;
      continue;
    }
    double most = -2;
    for (const Vec3d& g : set.generators) most = std::max(most, dot(m, g));
    if (most < -sinPad) return false;
  }
  for (const Vec3d& n : set.faces) {
    double most = -2;
    for (const Vec3d& c : corner) most = std::max(most, dot(n, c));
    if (most < -sinPad) return false;
  }
  return true;
}

}  // namespace glint
