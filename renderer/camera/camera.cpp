#include "camera/camera.h"

#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/avx2_clones.h"
#include "core/lanes.h"
#include "core/sampling.h"
#include "core/unit_vector.h"

namespace glint {

ImageWindow CameraDesc::imageWindow(int width, int height) const {
  if (window) return *window;
  const float halfHeight = projection == Projection::Perspective
                               ? std::tan(0.5f * vfovDegrees * kPi / 180.0f)
                               : 0.5f * orthoHeight;
  const float halfWidth = halfHeight * (static_cast<float>(width) / static_cast<float>(height));
  return {-halfWidth, halfWidth, -halfHeight, halfHeight};
}

Camera::Camera(const CameraDesc& desc, int width, int height) : desc_(desc) {
  const Vec3f back = desc.eye - desc.lookAt;
  if (!(length(back) > 0)) throw std::invalid_argument("eye and look_at are the same point");
  w_ = normalize(back);
  view_ = -w_;
  if (desc.imagePlaneNormal) {
    // Seed 000 §4.3: the image plane's normal given apart from the view direction d.
    const Vec3f n = normalize(*desc.imagePlaneNormal);
    const float cosine = dot(n, view_);
    // Below this the image plane nearly holds the view direction: a pixel spans thousands of
    // times its width along it.
    if (!(std::abs(cosine) >= 1e-3f))
      throw std::invalid_argument(
          "image_plane_normal is perpendicular to the view direction: the image plane would "
          "contain it");
    w_ = cosine < 0 ? n : -n;
  }
  // Only up's direction counts: one at any scale is taken as its unit vector.
  const Vec3f up = hasSafeLength(desc.up) ? desc.up : unitVector(desc.up);
  const Vec3f right = cross(up, w_);
  if (!(length(right) > 1e-6f * length(up)))
    throw std::invalid_argument(desc.imagePlaneNormal ? "up is parallel to image_plane_normal"
                                                      : "up is parallel to the viewing direction");
  u_ = normalize(right);
  v_ = cross(w_, u_);
  window_ = desc.imageWindow(width, height);
  checkRayRange();
  // Per ray, a multiply instead of a division.
  uPerPixel_ = (window_.r - window_.l) / static_cast<float>(width);
  vPerPixel_ = (window_.t - window_.b) / static_cast<float>(height);
  // In double: a window too small for float's per-pixel steps still has an aspect.
  const double ratio =
      (double(window_.r) - window_.l) / width * height / (double(window_.t) - window_.b);
  pixelAspectRatio_ = ratio > 0 && std::isfinite(ratio) ? ratio : 1;
}

void Camera::checkRayRange() const {
  // Every number a camera ray is made of stays within kMaxRayOrigin (core/ray.h), so that no
  // ray reaches Embree's assertions and no length overflows: each window value (an orthographic
  // ray starts at eye + s_u·u + s_v·v, a perspective one points along s_u·u + s_v·v + d), the
  // eye, the lens and the focus distance.
  const auto far = [](float x) { return !(std::fabs(x) <= kMaxRayOrigin); };
  if (far(window_.l) || far(window_.r) || far(window_.b) || far(window_.t)) {
    char text[160];
    std::snprintf(text, sizeof text, "[%g, %g, %g, %g]", double(window_.l), double(window_.r),
                  double(window_.b), double(window_.t));
    throw std::invalid_argument(std::string("the image window ") + text +
                                " reaches past ±1e18, beyond the range of rays Glint traces");
  }
  const float eye =
      std::max({std::fabs(desc_.eye.x), std::fabs(desc_.eye.y), std::fabs(desc_.eye.z)});
  const float lensReach = hasLens() ? desc_.apertureRadius : 0.0f;
  const float windowReach = desc_.projection == Projection::Orthographic
                                ? std::fabs(window_.l) + std::fabs(window_.r) +
                                      std::fabs(window_.b) + std::fabs(window_.t)
                                : 0.0f;
  if (far(eye + lensReach + windowReach))
    throw std::invalid_argument(
        "camera rays would start more than 1e18 from the origin (the eye, plus the lens or the "
        "orthographic window), beyond the range of rays Glint traces");
  if (hasLens() && !(desc_.focusDistance <= kMaxRayOrigin * 1e-3f))
    throw std::invalid_argument(
        "focus_distance is past 1e15, beyond the range of rays Glint traces");
}

void Camera::generateRay(float x, float y, Vec2f lens, Ray& ray) const {
  // Seed 000 eq. 4.1, with rows counted down from the top edge.
  const float su = window_.l + uPerPixel_ * x;
  const float sv = window_.t - vPerPixel_ * y;
  ray.tMin = 0;
  ray.tMax = kInfinity;
  ray.time = 0;
  ray.origin = ray_origin::kEye;
  if (desc_.projection == Projection::Perspective) {
    // Through s = e + d + u·u + v·v: the image plane at distance 1 along the view direction d,
    // spanned by u and v (§4.3.2; d = −w unless oblique).
    ray.o = desc_.eye;
    ray.d = normalize(su * u_ + sv * v_ + view_);
    if (hasLens()) {
      // Thin lens, parallel to the image plane: every ray through the lens point meets the
      // pinhole ray on the focus plane, parallel to the image plane at focus_distance.
      const Vec2f l = desc_.lensShape == LensShape::Disk ? squareToDiskConcentric(lens)
                                                         : Vec2f{2 * lens.x - 1, 2 * lens.y - 1};
      const Vec3f pFocus = ray.o + (desc_.focusDistance / dot(ray.d, -w_)) * ray.d;
      ray.o = desc_.eye + desc_.apertureRadius * (l.x * u_ + l.y * v_);
      ray.d = normalize(pFocus - ray.o);
    }
  } else {
    ray.o = desc_.eye + su * u_ + sv * v_;
    ray.d = view_;
  }
}

namespace {

using F32x4 = float __attribute__((vector_size(16)));

// Eight vectors side by side, and generateRay's vector operations on them, rounded in its order.
struct Vec3x8 {
  F32x8 x, y, z;
};
// Vectors pass to these by reference or in a struct: Clang refuses a 32-byte vector passed or
// returned by value between the AVX2 clone and a function built without AVX, inlined or not.
[[gnu::always_inline]] inline Vec3x8 normalize(const Vec3x8& a) {
  // The root in two halves through SSE: baseline x86-64 has no wider one; AVX2 code joins them.
  const F32x8 length2 = a.x * a.x + a.y * a.y + a.z * a.z;
  const F32x4 low = _mm_sqrt_ps(F32x4{length2[0], length2[1], length2[2], length2[3]});
  const F32x4 high = _mm_sqrt_ps(F32x4{length2[4], length2[5], length2[6], length2[7]});
  const F32x8 inverse = 1.0f / __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
  return {a.x * inverse, a.y * inverse, a.z * inverse};
}
// The x and y of points p[0 .. 7] into lanes.
[[gnu::always_inline]] inline void loadLanes(const Vec2f* p, F32x8& x, F32x8& y) {
  F32x8 low, high;
  std::memcpy(&low, p, sizeof low);
  std::memcpy(&high, p + 4, sizeof high);
  x = __builtin_shufflevector(low, high, 0, 2, 4, 6, 8, 10, 12, 14);
  y = __builtin_shufflevector(low, high, 1, 3, 5, 7, 9, 11, 13, 15);
}
// s·a + t·b.
[[gnu::always_inline]] inline Vec3x8 span(const F32x8& s, const Vec3f& a, const F32x8& t,
                                          const Vec3f& b) {
  return {a.x * s + b.x * t, a.y * s + b.y * t, a.z * s + b.z * t};
}

// out[l] = (a[l], b[l], c[l], d[l]) for the eight lanes.
[[gnu::always_inline]] inline void transposeLanes(const F32x8& a, const F32x8& b, const F32x8& c,
                                                  const F32x8& d, F32x4* out) {
  const F32x8 ab01 = __builtin_shufflevector(a, b, 0, 8, 1, 9, 4, 12, 5, 13);
  const F32x8 ab23 = __builtin_shufflevector(a, b, 2, 10, 3, 11, 6, 14, 7, 15);
  const F32x8 cd01 = __builtin_shufflevector(c, d, 0, 8, 1, 9, 4, 12, 5, 13);
  const F32x8 cd23 = __builtin_shufflevector(c, d, 2, 10, 3, 11, 6, 14, 7, 15);
  const F32x8 rows[4] = {__builtin_shufflevector(ab01, cd01, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(ab01, cd01, 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(ab23, cd23, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(ab23, cd23, 2, 3, 10, 11, 6, 7, 14, 15)};
  for (int r = 0; r < 4; ++r) {
    out[r] = __builtin_shufflevector(rows[r], rows[r], 0, 1, 2, 3);
    out[r + 4] = __builtin_shufflevector(rows[r], rows[r], 4, 5, 6, 7);
  }
}

// The layout the transposed stores write: o, d, tMin, tMax in the first 32 bytes.
static_assert(offsetof(Ray, o) == 0 && offsetof(Ray, d) == 12 && offsetof(Ray, tMin) == 24 &&
              offsetof(Ray, tMax) == 28 && sizeof(float) == 4);

// What Camera::generateRays reads of the camera.
struct RayFrame {
  Vec3f eye, u, v, view, negW;
  ImageWindow window;
  float uPerPixel, vPerPixel, focusDistance, apertureRadius;
  bool perspective, thinLens, disk;
};

// Camera::generateRays, eight rays side by side. Built for baseline x86-64 and for AVX2, chosen
// by what the CPU has: AVX2 holds eight lanes in one register, where a thin lens's chain of
// divisions and roots took two.
GLINT_AVX2_CLONES(void, raysInLanes,
                  (const RayFrame& c, const Vec2f* film, const Vec2f* lens, int n, Ray* out,
                   const int* slot),
                  (c, film, lens, n, out, slot)) {
  const bool perspective = c.perspective, thinLens = c.thinLens;
  const Vec3f eye = c.eye, negW = c.negW, u = c.u, v = c.v, view = c.view;
  for (int first = 0; first < n; first += 8) {
    F32x8 x, y, lx{}, ly{};
    if (first + 8 <= n) {
      loadLanes(film + first, x, y);
      if (thinLens) loadLanes(lens + first, lx, ly);
    } else {
      // Lanes past n repeat the last ray, so that every lane holds numbers from the film.
      Vec2f tail[2][8];
      for (int l = 0; l < 8; ++l) {
        tail[0][l] = film[std::min(first + l, n - 1)];
        if (thinLens) tail[1][l] = lens[std::min(first + l, n - 1)];
      }
      loadLanes(tail[0], x, y);
      if (thinLens) loadLanes(tail[1], lx, ly);
    }
    const F32x8 su = c.window.l + c.uPerPixel * x;
    const F32x8 sv = c.window.t - c.vPerPixel * y;
    Vec3x8 o{}, d{};
    if (perspective) {
      const Vec3x8 s = span(su, u, sv, v);
      d = normalize({s.x + view.x, s.y + view.y, s.z + view.z});
      if (thinLens) {
        F32x8 ex, ey;
        if (c.disk) {
          squareToDiskConcentricLanes(lx, ly, ex, ey);
        } else {
          ex = 2 * lx - 1;
          ey = 2 * ly - 1;
        }
        const F32x8 along = c.focusDistance / (d.x * negW.x + d.y * negW.y + d.z * negW.z);
        const Vec3x8 focus = {eye.x + d.x * along, eye.y + d.y * along, eye.z + d.z * along};
        const Vec3x8 e = span(ex, u, ey, v);
        const float a = c.apertureRadius;
        o = {eye.x + e.x * a, eye.y + e.y * a, eye.z + e.z * a};
        d = normalize({focus.x - o.x, focus.y - o.y, focus.z - o.z});
      }
    } else {
      o = {eye.x + u.x * su + v.x * sv, eye.y + u.y * su + v.y * sv, eye.z + u.z * su + v.z * sv};
    }
    // A pinhole's rays start at the eye, an orthographic camera's all point along view.
    if (perspective && !thinLens) o = {F32x8{} + eye.x, F32x8{} + eye.y, F32x8{} + eye.z};
    if (!perspective) d = {F32x8{} + view.x, F32x8{} + view.y, F32x8{} + view.z};
    // Each ray's first 32 bytes, (o, d.x) and (d.y, d.z, tMin, tMax), from the lanes by two
    // transposes: written a float at a time, each ray paid for six lane extractions.
    F32x4 front[8], back[8];
    transposeLanes(o.x, o.y, o.z, d.x, front);
    transposeLanes(d.y, d.z, F32x8{}, F32x8{} + kInfinity, back);
    for (int l = 0; l < 8 && first + l < n; ++l) {
      Ray& ray = out[slot[first + l]];
      std::memcpy(static_cast<void*>(&ray), &front[l], sizeof front[l]);
      std::memcpy(reinterpret_cast<char*>(&ray) + sizeof front[l], &back[l], sizeof back[l]);
      ray.time = 0;
      ray.origin = ray_origin::kEye;
    }
  }
}

}  // namespace

void Camera::generateRays(const Vec2f* film, const Vec2f* lens, int n, Ray* out,
                          const int* slot) const {
  const bool perspective = desc_.projection == Projection::Perspective;
  const RayFrame frame{desc_.eye,
                       u_,
                       v_,
                       view_,
                       -w_,
                       window_,
                       uPerPixel_,
                       vPerPixel_,
                       desc_.focusDistance,
                       desc_.apertureRadius,
                       perspective,
                       perspective && hasLens(),
                       desc_.lensShape == LensShape::Disk};
  raysInLanes(frame, film, lens, n, out, slot);
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
  // A camera-space point (x, y, z) lies on the ray of image-plane point (s_u, s_v) when
  // perspective: s_u = (c·x − d_u·z) / z, s_v = (c·y − d_v·z) / z; orthographic: s_u = x −
  // (d_u/c)·z, s_v = y − (d_v/c)·z; with d = (d_u, d_v, c) the view direction in camera space
  // (0, 0, 1 unless oblique). NDC is then ((s_u − l)/(r − l), (t − s_v)/(t − b)), divided by
  // the depth z under perspective (w' = z); z' = 1 makes z'/w' = 1/z, so the matrix stays
  // invertible and a tool can turn an NDC point back into a ray.
  const float du = dot(view_, u_), dv = dot(view_, v_), c = dot(view_, -w_);
  const ImageWindow& win = window_;
  const float width = win.r - win.l, height = win.t - win.b;
  Mat4 p;
  if (desc_.projection == Projection::Perspective) {
    p(0, 0) = c / width;
    p(0, 2) = -(du + win.l) / width;
    p(1, 1) = -c / height;
    p(1, 2) = (dv + win.t) / height;
    p(2, 2) = 0;
    p(2, 3) = 1;
    p(3, 2) = 1;
    p(3, 3) = 0;
  } else {
    p(0, 0) = 1 / width;
    p(0, 2) = -du / (c * width);
    p(0, 3) = -win.l / width;
    p(1, 1) = -1 / height;
    p(1, 2) = dv / (c * height);
    p(1, 3) = win.t / height;
  }
  return p * worldToCamera();
}

}  // namespace glint
