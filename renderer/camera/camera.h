#pragma once
// Viewing rays of seed 000 §4.3: perspective (vertical field of view) and orthographic (view
// height), with the camera frame u, v, w built from eye, look_at and up; an off-centre image
// window (l, r, b, t of eq. 4.1) and an image plane whose normal differs from the view direction
// (oblique parallel and oblique perspective views); and the thin lens of seed 000 §13.4.3
// (aperture radius, focus distance; disk or square lens).
#include <optional>

#include "core/ray.h"
#include "core/transform.h"

namespace glint {

enum class Projection { Perspective, Orthographic };
enum class LensShape { Disk, Square };

// The image's extent on the image plane (seed 000 eq. 4.1): u from l to r, v from b to t, at
// distance 1 from the eye (perspective) or in scene units from it (orthographic).
struct ImageWindow {
  float l = -1, r = 1, b = -1, t = 1;
};

struct CameraDesc {
  Projection projection = Projection::Perspective;
  Vec3f eye{0, 0, 0}, lookAt{0, 0, -1}, up{0, 1, 0};
  float vfovDegrees = 40;
  float orthoHeight = 2;
  // An off-centre window in place of the one vfov (or the view height) and the image's aspect
  // ratio give.
  std::optional<ImageWindow> window;
  // The image plane's normal, when it is not the view direction (an oblique view); either
  // orientation, not perpendicular to the view direction.
  std::optional<Vec3f> imagePlaneNormal;
  float apertureRadius = 0;  // 0 = pinhole
  float focusDistance = 1;
  LensShape lensShape = LensShape::Disk;
  float shutterOpen = 0, shutterClose = 0;

  // The window, or the centred one of vfov (or the view height) at the image's aspect ratio.
  ImageWindow imageWindow(int width, int height) const;
};

class Camera {
 public:
  Camera() = default;
  // Throws std::invalid_argument when eye == look_at, up is parallel to the image plane's
  // normal, the image plane is (nearly) parallel to the view direction, or its rays would leave
  // the range Glint traces (core/ray.h kMaxRayOrigin: the window, eye, lens, focus distance).
  Camera(const CameraDesc& desc, int width, int height);

  // A ray through film position (x, y) in pixels, y down from the top edge; `lens` in [0, 1)²
  // picks the point on the lens (ignored by a pinhole, which takes the same code path as
  // before the lens existed, so aperture 0 is the pinhole image bit for bit).
  Ray generateRay(float x, float y, Vec2f lens = {0.5f, 0.5f}) const {
    Ray ray;
    generateRay(x, y, lens, ray);
    return ray;
  }
  // The same, written into `ray` (all fields; a returned copy stalled on store forwarding).
  void generateRay(float x, float y, Vec2f lens, Ray& ray) const;
  // generateRay(film[i].x, film[i].y, lens[i], out[slot[i]]) for i in [0, n), the same bits;
  // `lens` may be null for a camera without one. Eight rays side by side: one at a time, a thin
  // lens's ray waited on its chain of divisions and square roots.
  void generateRays(const Vec2f* film, const Vec2f* lens, int n, Ray* out, const int* slot) const;
  bool hasLens() const { return desc_.apertureRadius > 0; }

  // OpenEXR's standard worldToCamera and worldToNDC (ImfStandardAttributes.h): camera space is
  // left-handed, the camera at the origin looking down +z, x right, y up; NDC has (0, 0) at the
  // top-left and (1, 1) at the bottom-right of the full image, after the divide by w. Here in
  // the column-vector convention p' = M·p; the EXR holds the transpose (Imath's p' = p·M).
  Mat4 worldToCamera() const;
  Mat4 worldToNdc() const;

  // A pixel's width over its height on the image plane: 1 unless a window's aspect differs
  // from the image's (OpenEXR's pixelAspectRatio, which compositors use to display the frame).
  double pixelAspectRatio() const { return pixelAspectRatio_; }

  const CameraDesc& desc() const { return desc_; }
  Vec3f u() const { return u_; }
  Vec3f v() const { return v_; }
  Vec3f w() const { return w_; }
  Vec3f viewDirection() const { return view_; }

 private:
  void checkRayRange() const;

  CameraDesc desc_;
  // Right, up and backwards: w is the image plane's normal turned towards the eye (without an
  // oblique plane, eye − look_at normalised), u = up × w, v = w × u.
  Vec3f u_, v_, w_;
  Vec3f view_;           // the projection direction (seed 000 §4.3's d), −w unless oblique
  ImageWindow window_;   // on the image plane at distance 1 (or in units, ortho)
  float uPerPixel_ = 1;  // (r − l) / width
  float vPerPixel_ = 1;  // (t − b) / height
  double pixelAspectRatio_ = 1;
};

}  // namespace glint
