#pragma once
// Affine maps in double precision, for the scene loader: scene files give positions in world
// space, possibly far from the origin, and composing transforms or shifting points there in
// float would round every coordinate to float's spacing at that distance (0.008 at 1e5) before
// the renderer ever saw it. The loader composes and places in double and rounds once, in render
// space (docs/scene-format.md, "Render space").
#include <array>

#include "core/transform.h"
#include "core/vec.h"

namespace glint {

struct Vec3d {
  double x = 0, y = 0, z = 0;

  friend constexpr Vec3d operator+(const Vec3d& a, const Vec3d& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
  }
  friend constexpr Vec3d operator-(const Vec3d& a, const Vec3d& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  friend constexpr Vec3d operator*(const Vec3d& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
  friend constexpr bool operator==(const Vec3d&, const Vec3d&) = default;
};

constexpr Vec3d toDouble(const Vec3f& v) { return {v.x, v.y, v.z}; }
constexpr Vec3f toFloat(const Vec3d& v) { return {float(v.x), float(v.y), float(v.z)}; }

// m · translate(t) in double: a map of render space (world − t) applied to world points.
Mat4 afterTranslation(const Mat4& m, const Vec3d& t);

// p' = L·p + t, stored row-major as the top three rows of a 4×4 matrix.
class Affine {
 public:
  Affine() = default;  // the identity
  static Affine translate(const Vec3d& t);
  static Affine scale(const Vec3d& s);
  // Rodrigues' formula; 90° turns land on exact zeros. Throws std::invalid_argument for a
  // zero-length axis.
  static Affine rotate(const Vec3d& axis, double degrees);
  // From a row-major 4×4 whose last row is [0, 0, 0, 1] (checked by toTransform()).
  static Affine fromRows(const std::array<double, 12>& rows);

  friend Affine operator*(const Affine& a, const Affine& b);
  Vec3d point(const Vec3d& p) const;
  // Rounded to float for the renderer; throws std::invalid_argument when singular.
  Transform toTransform() const;

 private:
  std::array<double, 12> m_{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
};

}  // namespace glint
