#pragma once
// The visibility sets of Ohta and Maekawa's ray coherence (seed 002 §9.2.4, eq. 9.20):
// V(o1, o2), the directions of the rays that leave o1 and meet o2, and the direction classes of
// the subdivided direction cube (figure 9.6) that such a set meets.
//
// Shells stand for objects: a sphere (exact for a sphere), or a convex polytope given by its
// vertices (exact for a quad; a box's eight corners bound everything else: meshes, disks, CSG
// solids, instances, and moving objects over the whole shutter). The sets are the seed's:
//  - two spheres: the spherical circle around c2 − c1 of radius arcsin((r1 + r2)/|c2 − c1|), the
//    whole sphere of directions when they overlap (the Minkowski difference o2 − o1 is the ball
//    of radius r1 + r2 around c2 − c1);
//  - anything with a polytope: the spherical convex hull of the directions v2 − v1 over the
//    vertex pairs (o2 − o1 is the convex hull of those differences), a sphere standing in as its
//    box's corners; the whole sphere when the two shells' boxes are not apart along some axis
//    (then the difference may hold 0).
// Every set is padded by `pad` in space (each shell grown by it: the offset that puts a spawned
// ray a hair off its surface, and the rounding of hit points) and by kAnglePad in angle (the
// rounding of a direction's class); the test of a set against a class is conservative, never
// leaving out a class the padded set meets.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/affine.h"
#include "core/bounds.h"
#include "core/vec.h"

namespace glint {

struct Shell {
  bool sphere = false;
  Vec3d center;  // a sphere's
  double radius = 0;
  std::vector<Vec3d> vertices;  // a polytope's (a sphere: its box's corners)
  Vec3d lo, hi;                 // the box around it

  static Shell ofSphere(const Vec3f& center, float radius);
  static Shell ofBox(const Bounds3f& box);
  static Shell ofPolygon(const std::vector<Vec3f>& vertices);
  // Whether p lies in the shell grown by `pad` (a sphere's ball; a polytope's box).
  bool holds(const Vec3f& p, double pad) const;
};

// The angle added to every set for the rounding of a float direction's class.
inline constexpr double kAnglePad = 1e-5;

struct VisibilitySet {
  bool everywhere = false;        // every direction
  Vec3d axis{0, 0, 1};            // a spherical cap around `axis` of angle `halfAngle` that holds
  double halfAngle = 0;           //   the set (exactly it, for a sphere pair), padded
  double pad = 0;                 // the angle the generators' hull is widened by
  std::vector<Vec3d> generators;  // unit; the set is their spherical hull (empty: the cap)
  std::vector<Vec3d> faces;       // unit inward normals of the hull's planes through 0
};

// V(from, to) for rays leaving `from`, each shell grown by `pad`.
VisibilitySet visibilitySet(const Shell& from, const Shell& to, double pad);

// A lower bound on the distance between a point of `from` and a point of `to`, each shell grown
// by `pad` (0 when they may touch): between the spheres, else between the boxes.
double shellDistance(const Shell& from, const Shell& to, double pad);

// The direction cube's six faces, each cut into resolution × resolution classes: face a·2 + s
// holds the directions whose largest component is along axis a, positive (s = 0) or negative;
// on it, u and v are the next two axes' components over the largest one's magnitude, in [−1, 1].
class DirectionClasses {
 public:
  explicit DirectionClasses(int resolution) : r_(resolution) {}
  int resolution() const { return r_; }
  uint32_t count() const { return 6u * uint32_t(r_) * uint32_t(r_); }
  // The class of d (finite, not 0: the caller checks).
  uint32_t classOf(const Vec3f& d) const {
    const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    const int a = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    const float m = d[a], size = std::fabs(m);
    // Divided, not multiplied by 1/size, which overflows for a subnormal size.
    const float u = d[(a + 1) % 3] / size, v = d[(a + 2) % 3] / size;
    const auto cell = [&](float x) {
      const int i = static_cast<int>((x + 1) * 0.5f * float(r_));
      return uint32_t(i < 0 ? 0 : i >= r_ ? r_ - 1 : i);
    };
    const uint32_t face = uint32_t(2 * a + (m < 0));
    return (face * uint32_t(r_) + cell(u)) * uint32_t(r_) + cell(v);
  }
  // Calls add(class) for every class that `set` may meet (a superset of those it meets), each
  // once, by quartering the faces down to single classes where the set may meet a block.
  template <class Add>
  void forEachClassMeeting(const VisibilitySet& set, Add&& add) const;

  // Whether `set` may meet the block [u0, u1] × [v0, v1] of `face` (false only when it does
  // not). Exposed for the tests.
  bool mayMeet(const VisibilitySet& set, int face, double u0, double u1, double v0,
               double v1) const;
  // Whether the block lies inside `set` (false when unsure): its classes are listed without
  // looking at each.
  bool inside(const VisibilitySet& set, int face, double u0, double u1, double v0, double v1) const;

 private:
  template <class Add>
  void descend(const VisibilitySet& set, int face, int i0, int i1, int j0, int j1, Add& add) const;
  int r_;
};

template <class Add>
void DirectionClasses::forEachClassMeeting(const VisibilitySet& set, Add&& add) const {
  for (int face = 0; face < 6; ++face) descend(set, face, 0, r_, 0, r_, add);
}

// Classes [i0, i1) × [j0, j1) of `face`.
template <class Add>
void DirectionClasses::descend(const VisibilitySet& set, int face, int i0, int i1, int j0, int j1,
                               Add& add) const {
  const double step = 2.0 / r_;
  const double u0 = -1 + i0 * step, u1 = -1 + i1 * step, v0 = -1 + j0 * step, v1 = -1 + j1 * step;
  if (!set.everywhere && !mayMeet(set, face, u0, u1, v0, v1)) return;
  if ((i1 - i0 == 1 && j1 - j0 == 1) || set.everywhere || inside(set, face, u0, u1, v0, v1)) {
    for (int i = i0; i < i1; ++i)
      for (int j = j0; j < j1; ++j)
        add((uint32_t(face) * uint32_t(r_) + uint32_t(i)) * uint32_t(r_) + uint32_t(j));
    return;
  }
  const int im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1, jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
  descend(set, face, i0, im, j0, jm, add);
  if (im < i1) descend(set, face, im, i1, j0, jm, add);
  if (jm < j1) descend(set, face, i0, im, jm, j1, add);
  if (im < i1 && jm < j1) descend(set, face, im, i1, jm, j1, add);
}

}  // namespace glint
