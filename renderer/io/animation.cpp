#include "io/animation.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

// Embree's time steps are evenly spaced, so a frame's motion is resampled at evenly spaced
// times. Where an original key (a bend in the path) falls inside the shutter, the smallest count
// that puts a sample exactly on every such key is used; past this many the path between samples
// is approximated by straight segments.
constexpr size_t kMaxFrameKeys = 33;

std::string rangeText(const Animation& a) {
  return std::to_string(a.first) + "-" + std::to_string(a.last);
}

// Samples (count ≥ 1) at evenly spaced times over [t0, t1] that land on every key time strictly
// inside it, when some count up to kMaxFrameKeys does.
size_t sampleCount(const Animation& a, size_t keyCount, double t0, double t1) {
  if (!(t1 > t0)) return 1;
  std::vector<double> bends;  // where the path bends inside the shutter, as a fraction of it
  for (size_t k = 0; k < keyCount; ++k) {
    const double t = a.first + double(k) * double(a.last - a.first) / double(keyCount - 1);
    if (t > t0 && t < t1) bends.push_back((t - t0) / (t1 - t0));
  }
  for (size_t m = 2; m < kMaxFrameKeys; ++m) {
    const bool onGrid = std::all_of(bends.begin(), bends.end(), [&](double u) {
      const double j = u * double(m - 1);
      return std::abs(j - std::round(j)) < 1e-9;
    });
    if (onGrid) return m;
  }
  return kMaxFrameKeys;
}

Vec3f lerp(const Vec3f& a, const Vec3f& b, float f) { return (1 - f) * a + f * b; }

std::vector<Vec3f> lerp(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b, float f) {
  std::vector<Vec3f> out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = (1 - f) * a[i] + f * b[i];
  return out;
}

// The value of `keys` at `p`; exactly a key when p sits on one, so a frame on a key equals a still
// scene with the object there, bit for bit (slerp at 0 need not return its first argument).
template <typename T>
T valueAt(const std::vector<T>& keys, const KeyPosition& p) {
  if (p.fraction == 0) return keys[p.segment];
  if (p.fraction == 1) return keys[p.segment + 1];
  return lerp(keys[p.segment], keys[p.segment + 1], static_cast<float>(p.fraction));
}

// `keys` (spread over the animation) → keys spread evenly over [t0, t1]; one key when t0 = t1.
template <typename T>
std::vector<T> resample(const std::vector<T>& keys, const Animation& a, double t0, double t1) {
  const size_t count = sampleCount(a, keys.size(), t0, t1);
  std::vector<T> out;
  out.reserve(count);
  for (size_t j = 0; j < count; ++j) {
    const double t = j == 0 ? t0 : t0 + (t1 - t0) * double(j) / double(count - 1);
    out.push_back(valueAt(keys, keyPosition(a, keys.size(), t)));
  }
  // As the loader does for equal keys: no motion within this frame is a static object, which
  // renders exactly as one without keys.
  if (std::all_of(out.begin(), out.end(), [&](const T& k) { return k == out[0]; })) out.resize(1);
  return out;
}

Vec3d lerp(const Vec3d& a, const Vec3d& b, double f) {
  return {(1 - f) * a.x + f * b.x, (1 - f) * a.y + f * b.y, (1 - f) * a.z + f * b.z};
}

}  // namespace

std::optional<Animation> parseAnimation(const std::optional<JsonNode>& node,
                                        std::optional<int> frame) {
  if (!node) {
    if (frame)
      throw UsageError("--frame " + std::to_string(*frame) +
                       ": the scene is not animated (it declares no \"animation\")");
    return std::nullopt;
  }
  node->checkKeys({"frames"});
  const JsonNode frames = node->at("frames");
  if (!frames.isArray() || frames.size() != 2) frames.fail("must be [first, last]");
  Animation a;
  a.first = frames[0].integer(0, 9999999);
  a.last = frames[1].integer(0, 9999999);
  // Keys are spread over the frames between the two; with one frame there is nothing to spread.
  if (a.last <= a.first) frames.fail("the last frame must come after the first");
  a.frame = frame.value_or(a.first);
  if (a.frame < a.first || a.frame > a.last)
    throw UsageError("--frame " + std::to_string(a.frame) + " is outside the scene's frames " +
                     rangeText(a) + " (animation.frames)");
  return a;
}

KeyPosition keyPosition(const Animation& a, size_t keyCount, double frame) {
  if (keyCount < 2) return {};
  const double last = double(keyCount - 1);
  // For an integer frame (t − A)(K − 1) is an exact integer, and the division is exact whenever
  // the frame sits on a key.
  const double s =
      std::clamp((frame - double(a.first)) * last / double(a.last - a.first), 0.0, last);
  const size_t segment = std::min(static_cast<size_t>(s), keyCount - 2);
  return {segment, s - double(segment)};
}

CameraPose parseCameraPose(const JsonNode& n, const std::optional<Animation>& animation) {
  if (!n.has("keys"))
    return {n.at("eye").vec3d(), n.at("look_at").vec3d(), n.vec3("up", {0, 1, 0})};
  const JsonNode keys = n.at("keys");
  for (const std::string key : {"eye", "look_at", "up"})
    if (n.has(key))
      n.at(key).fail("the camera's \"keys\" replace eye, look_at and up: give one or the other");
  if (!animation)
    keys.fail(
        "camera keys are spread over the frames of an animation: add \"animation\": "
        "{\"frames\": [first, last]}");
  if (!keys.isArray() || keys.size() < 2)
    keys.fail("must list at least 2 keys (spread evenly over the animation's frames)");
  std::vector<CameraPose> poses;
  for (const JsonNode& k : keys.elements()) {
    k.checkKeys({"eye", "look_at", "up"});
    CameraPose p{k.at("eye").vec3d(), k.at("look_at").vec3d(), k.vec3("up", {0, 1, 0})};
    if (p.eye == p.lookAt) k.fail("eye and look_at are the same point");
    poses.push_back(p);
  }
  // The camera sits at the frame's own time: it is not motion-blurred.
  const KeyPosition at = keyPosition(*animation, poses.size(), animation->frame);
  const CameraPose &a = poses[at.segment], &b = poses[at.segment + 1];
  if (at.fraction == 0) return a;
  if (at.fraction == 1) return b;
  const float f = static_cast<float>(at.fraction);
  return {lerp(a.eye, b.eye, at.fraction), lerp(a.lookAt, b.lookAt, at.fraction),
          (1 - f) * a.up + f * b.up};
}

void resampleMotionToFrame(Scene& s, const Animation& a) {
  CameraDesc& c = s.cameraDesc;
  const double t0 = a.frame + double(c.shutterOpen), t1 = a.frame + double(c.shutterClose);
  for (size_t i = 0; i < s.spheres.size(); ++i) {
    std::vector<Vec3f>& keys = s.sphereCenterKeys[i];
    if (keys.empty()) continue;
    keys = resample(keys, a, t0, t1);
    s.spheres[i].center = keys[0];
    if (keys.size() == 1) keys.clear();
  }
  for (TriangleMesh& m : s.meshes) {
    if (!m.deforming()) continue;
    m.positionKeys = resample(m.positionKeys, a, t0, t1);
    m.positions = m.positionKeys[0];
    if (m.positionKeys.size() == 1) m.positionKeys.clear();
    m.padForEmbree();
  }
  for (Instance& inst : s.instances) {
    if (inst.motion.empty()) continue;
    inst.motion = resample(inst.motion, a, t0, t1);
    inst.worldFromObject = inst.motion[0].toTransform();
    if (inst.motion.size() == 1) inst.motion.clear();
  }
  // The resampled keys span exactly the frame's shutter, which is now all of normalised time.
  c.shutterOpen = 0;
  c.shutterClose = t1 > t0 ? 1.0f : 0.0f;
}

}  // namespace glint
