#pragma once
// Where the loader puts things. The renderer works in float, like Embree; a scene placed far
// from the world origin (a set at 1e5 units) would lose its small details to float's spacing
// there (0.008 at 1e5). So the loader reads positions in double, composes transforms in double,
// and hands the renderer *render space*: world space shifted so the camera's eye sits at the
// origin (camera-relative rendering). Every coordinate is rounded to float once, after the
// shift, where float is finest near the viewer. Scene::worldOrigin keeps the shift so outputs
// that name world positions (the position AOV, the worldToCamera metadata) add it back.
#include "core/affine.h"
#include "io/json_source.h"

namespace glint {

// One object's local coordinates → render space.
class Placement {
 public:
  Placement() = default;  // the identity
  // Throws std::invalid_argument when the map is singular once rounded to float.
  explicit Placement(const Affine& toRender) : affine_(toRender), xf_(toRender.toTransform()) {}

  Vec3f point(const Vec3d& local) const { return toFloat(affine_.point(local)); }
  Vec3f point(const JsonNode& local) const { return point(local.vec3d()); }
  // The float transform: vectors, normals, the determinant, and Embree instances.
  const Transform& transform() const { return xf_; }
  const Affine& affine() const { return affine_; }

 private:
  Affine affine_;
  Transform xf_;
};

}  // namespace glint
