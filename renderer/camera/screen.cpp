#include "camera/screen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace glint {

namespace {

double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

}  // namespace

ScreenView viewThroughScreen(const Vec3d& eye, const Vec3d& cornerMin, const Vec3d& cornerMax,
                             const Vec3f& up) {
  const Vec3d diagonal = cornerMax - cornerMin;
  const double halfDiagonal = 0.5 * length(diagonal);
  if (!(halfDiagonal > 0))
    throw std::invalid_argument(
        "corner_min and corner_max are the same point: the window has no extent");
  const Vec3d centre = (cornerMin + cornerMax) * 0.5;
  const Vec3d toEye = eye - centre;
  const double h = length(toEye);
  if (!(h > kScreenMinDistance * halfDiagonal))
    throw std::invalid_argument(
        "the eye lies in the window's plane (its distance to the window's centre, " + number(h) +
        ", is not above 1e-3 of the half-diagonal, " + number(halfDiagonal) +
        "): it would see the window edge-on");
  const double toMin = length(cornerMin - eye), toMax = length(cornerMax - eye);
  if (!(std::fabs(toMax - toMin) <= kScreenEquidistance * std::max(toMin, toMax)))
    throw std::invalid_argument(
        "the corners are not equidistant from the eye (corner_min at " + number(toMin) +
        ", corner_max at " + number(toMax) +
        "; they must agree to 1 part in 1e4): the window would be tilted against the line of "
        "sight and the image distorted (seed 001 §8)");
  // The frame of camera.h with w the line of sight turned back towards the eye.
  const Vec3d w = toEye * (1 / h);
  const Vec3d right = cross(toDouble(up), w);
  if (!(length(right) > 1e-6 * length(toDouble(up))))
    throw std::invalid_argument(
        "up is parallel to the line of sight from the eye to the window's centre");
  const Vec3d u = right * (1 / length(right));
  const Vec3d v = cross(w, u);
  const double width = dot(diagonal, u), height = dot(diagonal, v);
  // Corners on one level (or one vertical) line: no window to look through, whichever corner
  // is named first.
  const double flat = 1e-6 * 2 * halfDiagonal;
  if (!(std::fabs(width) > flat && std::fabs(height) > flat))
    throw std::invalid_argument(
        "corner_max − corner_min runs " + number(width) + " along the window's right and " +
        number(height) + " along its up, as seen from the eye with this up: the window has no " +
        (std::fabs(height) > flat ? "width" : "height"));
  if (!(width > 0 && height > 0))
    throw std::invalid_argument(
        "corner_max − corner_min runs " + number(width) + " along the window's right and " +
        number(height) +
        " along its up: corner_min must be the window's lower-left corner and corner_max "
        "its upper-right, as seen from the eye with this up");
  const auto halfSpan = [h](double extent) { return static_cast<float>(0.5 * extent / h); };
  return {centre, {-halfSpan(width), halfSpan(width), -halfSpan(height), halfSpan(height)}};
}

}  // namespace glint
