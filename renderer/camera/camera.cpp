#include "camera/camera.h"

#include <cmath>
#include <stdexcept>

#include "core/sampling.h"

namespace glint {

Camera::Camera(const CameraDesc& desc, int width, int height) : desc_(desc) {
  const Vec3f back = desc.eye - desc.lookAt;
  if (!(length(back) > 0)) throw std::invalid_argument("eye and look_at are the same point");
  w_ = normalize(back);
  const Vec3f right = cross(desc.up, w_);
  if (!(length(right) > 1e-6f * length(desc.up)))
    throw std::invalid_argument("up is parallel to the viewing direction");
  u_ = normalize(right);
  v_ = cross(w_, u_);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  if (desc.projection == Projection::Perspective)
    halfHeight_ = std::tan(0.5f * desc.vfovDegrees * kPi / 180.0f);
  else
    halfHeight_ = 0.5f * desc.orthoHeight;
  halfWidth_ = halfHeight_ * aspect;
  // Per ray, a multiply instead of a division.
  uPerPixel_ = 2 * halfWidth_ / static_cast<float>(width);
  vPerPixel_ = 2 * halfHeight_ / static_cast<float>(height);
}

void Camera::generateRay(float x, float y, Vec2f lens, Ray& ray) const {
  // Seed 000 eq. 4.1 with l = −halfWidth, r = halfWidth, b = −halfHeight, t = halfHeight.
  const float su = -halfWidth_ + uPerPixel_ * x;
  const float sv = halfHeight_ - vPerPixel_ * y;
  ray.tMin = 0;
  ray.tMax = kInfinity;
  ray.time = 0;
  if (desc_.projection == Projection::Perspective) {
    ray.o = desc_.eye;
    ray.d = normalize(su * u_ + sv * v_ - w_);
    if (hasLens()) {
      // Thin lens: every ray through the lens point meets the pinhole ray on the focus plane,
      // at distance focus_distance along the view direction −w.
      const Vec2f l = desc_.lensShape == LensShape::Disk ? squareToDiskConcentric(lens)
                                                         : Vec2f{2 * lens.x - 1, 2 * lens.y - 1};
      const Vec3f pFocus = ray.o + (desc_.focusDistance / dot(ray.d, -w_)) * ray.d;
      ray.o = desc_.eye + desc_.apertureRadius * (l.x * u_ + l.y * v_);
      ray.d = normalize(pFocus - ray.o);
    }
  } else {
    ray.o = desc_.eye + su * u_ + sv * v_;
    ray.d = -w_;
  }
}

Mat4 Camera::worldToCamera() const {
  // OpenEXR's camera space is left-handed, looking down +z: rows u, v and −w (Glint's w points
  // backwards).
  Mat4 m;
  const Vec3f axes[3] = {u_, v_, -w_};
  for (int r = 0; r < 3; ++r) {
    m(r, 0) = axes[r].x;
    m(r, 1) = axes[r].y;
    m(r, 2) = axes[r].z;
    m(r, 3) = -dot(axes[r], desc_.eye);
  }
  return m;
}

Mat4 Camera::worldToNdc() const {
  // Camera (x, y, z) to NDC: x/(2·halfWidth) + 1/2 and 1/2 − y/(2·halfHeight), divided by the
  // depth z under perspective (w' = z). z' = 1 makes z'/w' = 1/z, so the matrix stays
  // invertible and a tool can turn an NDC point back into a ray.
  Mat4 p;
  p(0, 0) = 0.5f / halfWidth_;
  p(1, 1) = -0.5f / halfHeight_;
  if (desc_.projection == Projection::Perspective) {
    p(0, 2) = 0.5f;
    p(1, 2) = 0.5f;
    p(2, 2) = 0;
    p(2, 3) = 1;
    p(3, 2) = 1;
    p(3, 3) = 0;
  } else {
    p(0, 3) = 0.5f;
    p(1, 3) = 0.5f;
  }
  return p * worldToCamera();
}

}  // namespace glint
