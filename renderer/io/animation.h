#pragma once
// Animated scenes (docs/scene-format.md#animation). `"animation": {"frames": [A, B]}` spreads
// the objects' motion keys, and the camera's `keys`, evenly over frames A … B instead of over one
// shutter. A loaded Scene is always a single frame F: the camera is evaluated at time F, and
// every moving object's keys are resampled over the frame's shutter [F + open, F + close] (in
// frames), so the rest of the renderer sees an ordinary scene whose motion covers just that
// frame — or no motion at all when the shutter is closed.
#include <optional>

#include "io/json_source.h"
#include "scene/scene.h"

namespace glint {

// Reads the top-level "animation" (absent: a still scene, nullopt) and picks the frame: `frame`
// when given, else the first. A frame outside the range, or asked of a still scene, is a
// UsageError naming the range.
std::optional<Animation> parseAnimation(const std::optional<JsonNode>& node,
                                        std::optional<int> frame);

// Where time `frame` (in frames, fractional within a shutter) falls among `keyCount` keys spread
// evenly over the animation: s = (t − A)(K − 1)/(B − A), clamped to [0, K − 1], as a segment
// and the fraction along it. Integer arithmetic where it can, so a frame on a key is exactly it.
struct KeyPosition {
  size_t segment = 0;
  double fraction = 0;
};
KeyPosition keyPosition(const Animation& a, size_t keyCount, double frame);

// The camera's eye, look_at and up: its own keys, or for an animated scene its "keys" evaluated
// at the frame (eye and look_at linearly in double, before the shift into render space; up
// linearly). Checks that a camera gives one or the other and that keys have an animation.
struct CameraPose {
  Vec3d eye, lookAt;
  Vec3f up{0, 1, 0};
};
CameraPose parseCameraPose(const JsonNode& camera, const std::optional<Animation>& animation);

// Resamples every key list of the scene (sphere centres, mesh positions, instance transforms),
// read as spread over the animation, over the frame's shutter; afterwards they are spread over
// normalised time [0, 1] = that shutter, which becomes the camera's shutter. A closed shutter
// leaves each object static at the frame's time.
void resampleMotionToFrame(Scene& scene, const Animation& animation);

}  // namespace glint
