#pragma once
// Seed 001 §8's camera: the eye, and two opposite corners of the screen window in world space,
// equidistant from the eye. Glint has one camera model (camera.h): the screen is turned into
// its look_at and window when the scene loads.
//
// The eye looks at the window's centre, and the window stands perpendicular to that line of
// sight, which is what equidistant corners mean: |corner − eye|² = h² + |corner − centre|² for
// both corners exactly when the diagonal is perpendicular to the line of sight, h the eye's
// distance to the centre. `up` turns the window about the line of sight, as it turns a look_at
// camera; corner_min is then the window's lower-left corner and corner_max its upper-right.
#include "camera/camera.h"
#include "core/affine.h"

namespace glint {

// The corners' distances from the eye may differ by this much of the larger before the window
// counts as tilted: one part in 10⁴, far above the rounding of the corners written in decimal,
// far below a tilt anyone would draw on purpose.
inline constexpr double kScreenEquidistance = 1e-4;
// The eye's distance to the window's plane must be more than this share of the half-diagonal:
// nearer, the view would be wider than 179.9° (camera.vfov's limit) along the diagonal.
inline constexpr double kScreenMinDistance = 1e-3;

struct ScreenView {
  Vec3d lookAt;        // the window's centre
  ImageWindow window;  // at distance 1 from the eye, centred (camera.h)
};

// The look_at + window form of the screen (eye, corners in world space). Throws
// std::invalid_argument, saying which rule the screen breaks, when the corners coincide, the eye
// is at (or nearly at) the window's centre, the corners are not equidistant from the eye, up
// is parallel to the line of sight, the corners lie on one line along the window's right or up
// (an eye in the corners' plane but off the centre), or corner_min is not the lower-left corner
// as seen with up.
ScreenView viewThroughScreen(const Vec3d& eye, const Vec3d& cornerMin, const Vec3d& cornerMax,
                             const Vec3f& up);

}  // namespace glint
