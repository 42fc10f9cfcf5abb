// The camera (docs/scene-format.md#camera): look_at and vfov (or height), an off-centre window,
// an oblique image plane, a lens, the shutter; or seed 001 §8's screen corners.
#include <cmath>
#include <stdexcept>

#include "camera/screen.h"
#include "io/animation.h"
#include "io/scene_builder.h"

namespace glint {

namespace {

// "window": [l, r, b, t] with l < r and b < t (seed 000 eq. 4.1).
ImageWindow parseWindow(const JsonNode& n) {
  if (!n.isArray() || n.size() != 4) n.fail("must be [l, r, b, t]");
  const ImageWindow w{n[0].number(), n[1].number(), n[2].number(), n[3].number()};
  if (!(w.l < w.r)) n.fail("l must be less than r");
  if (!(w.b < w.t)) n.fail("b must be less than t");
  // Within ±kMaxRayOrigin every span (r − l, t − b) is a float and every ray it makes is one
  // Embree takes (camera/camera.cpp checks the derived rays again).
  for (size_t i = 0; i < 4; ++i)
    if (!(std::fabs(n[i].number()) <= kMaxRayOrigin))
      n[i].fail(
          "window values must lie within ±1e18 (the range of rays Glint traces; r − l "
          "and t − b must be floats)");
  return w;
}

// The lens: "aperture_radius", or a photographer's "focal_length" F and "f_number" a (seed 002
// §9.3: the lens diameter is D = F/a, so the radius F/(2a)).
void parseLens(const JsonNode& n, CameraDesc& c) {
  const bool byRadius = n.has("aperture_radius");
  const bool byNumber = n.has("focal_length") || n.has("f_number");
  if (byRadius && byNumber)
    n.at("aperture_radius")
        .fail(
            "is given with focal_length / f_number: give the lens one way (aperture_radius = "
            "focal_length / (2 f_number))");
  if (byRadius) c.apertureRadius = n.at("aperture_radius").number(0, 3.4e38f);
  if (byNumber) {
    for (const char* key : {"focal_length", "f_number"})
      if (!n.has(key))
        n.fail(std::string("focal_length and f_number go together: ") + key + " is missing");
    const float focalLength = n.at("focal_length").number(0, 3.4e38f, true);
    const float fNumber = n.at("f_number").number(0, 3.4e38f, true);
    c.apertureRadius = focalLength / (2 * fNumber);
  }
}

// Seed 001 §8's screen: "screen": {"corner_min": [x, y, z], "corner_max": [x, y, z]} with the
// eye and up, in place of look_at and the window (camera/screen.h).
CameraPose parseScreen(const JsonNode& n, CameraDesc& c) {
  for (const char* key : {"look_at", "vfov", "window", "image_plane_normal", "keys"})
    if (n.has(key))
      n.at(key).fail(
          "is given with \"screen\": the screen's corners set where the camera looks, the image "
          "plane and its extent themselves");
  const JsonNode screen = n.at("screen");
  screen.checkKeys({"corner_min", "corner_max"});
  const Vec3d eye = n.at("eye").vec3d();
  const Vec3f up = n.vec3("up", {0, 1, 0});
  const Vec3d cornerMin = screen.at("corner_min").vec3d();
  const Vec3d cornerMax = screen.at("corner_max").vec3d();
  try {
    const ScreenView view = viewThroughScreen(eye, cornerMin, cornerMax, up);
    c.window = view.window;
    return {eye, view.lookAt, up};
  } catch (const std::invalid_argument& e) {
    screen.fail(e.what());
  }
}

}  // namespace

void parseCamera(const JsonNode& n, const std::optional<Animation>& animation, CameraDesc& c,
                 Vec3d& origin) {
  const std::string type =
      n.has("type") ? n.at("type").choice({"perspective", "orthographic"}) : "perspective";
  c.projection = type == "perspective" ? Projection::Perspective : Projection::Orthographic;
  if (c.projection == Projection::Orthographic && n.has("screen"))
    n.at("screen").fail(
        "is a perspective camera's (seed 001 §8: the eye looks through the window); an "
        "orthographic view is set by look_at and height or window");
  // The window replaces the extent that vfov (or height) would give.
  const char* extent = c.projection == Projection::Perspective ? "vfov" : "height";
  if (n.has("window") && n.has(extent))
    n.at("window").fail(std::string("is given with ") + extent +
                        ": the window sets the image's extent itself");
  if (c.projection == Projection::Perspective) {
    n.checkKeys({"type", "eye", "look_at", "up", "vfov", "window", "image_plane_normal",
                 "aperture_radius", "focal_length", "f_number", "focus_distance", "lens", "shutter",
                 "keys", "screen"});
    if (auto v = n.get("vfov")) c.vfovDegrees = v->number(0, 179.9f, true);
  } else {
    n.checkKeys({"type", "eye", "look_at", "up", "height", "window", "image_plane_normal",
                 "shutter", "keys"});
    if (!n.has("window")) c.orthoHeight = n.at("height").number(0, 3.4e38f, true);
  }
  if (auto v = n.get("window")) c.window = parseWindow(*v);
  if (auto v = n.get("image_plane_normal")) c.imagePlaneNormal = v->direction();
  // Render space puts the eye at the origin (io/placement.h): an animated camera's eye at this
  // frame, so each frame is rendered around its own viewpoint.
  const CameraPose pose = n.has("screen") ? parseScreen(n, c) : parseCameraPose(n, animation);
  origin = pose.eye;
  c.eye = {0, 0, 0};
  c.lookAt = toFloat(pose.lookAt - origin);
  c.up = pose.up;
  parseLens(n, c);
  if (auto v = n.get("lens"))
    c.lensShape = v->choice({"disk", "square"}) == "disk" ? LensShape::Disk : LensShape::Square;
  c.focusDistance = length(c.lookAt - c.eye);
  if (auto v = n.get("focus_distance")) c.focusDistance = v->number(0, 3.4e38f, true);
  // Eq. 9.24: a lens brings to focus on the film only what lies beyond its focal length.
  if (auto f = n.get("focal_length"); f && !(c.focusDistance > f->number()))
    (n.has("focus_distance") ? n.at("focus_distance") : n)
        .fail("the focus distance " + formatNumber(c.focusDistance) +
              " is not beyond the focal length " + formatNumber(f->number()) +
              ": a lens focuses only on what lies farther than its focal length");
  if (auto v = n.get("shutter")) {
    if (v->size() != 2) v->fail("must be [open, close]");
    c.shutterOpen = (*v)[0].number(0, 1);
    c.shutterClose = (*v)[1].number(0, 1);
    if (c.shutterClose < c.shutterOpen) v->fail("close must not be before open");
  }
  try {
    Camera check(c, 1, 1);
  } catch (const std::invalid_argument& e) {
    // Each key was checked on its own: an animated camera fails where its keys blend.
    if (n.has("keys") && animation) {
      const JsonNode keys = n.at("keys");
      const size_t k = keyPosition(*animation, keys.size(), animation->frame).segment;
      keys.fail("at frame " + std::to_string(animation->frame) + ", between keys[" +
                std::to_string(k) + "] and keys[" + std::to_string(k + 1) + "]: " + e.what());
    }
    n.fail(e.what());
  }
}

}  // namespace glint
