#pragma once
// Motion keys: a transform given as scale, rotation (unit quaternion) and translation, so that
// keys interpolate the way Embree's quaternion motion does — scale and translation linearly,
// rotation by slerp — and a list of keys spread evenly over normalised time [0, 1].
#include <algorithm>
#include <vector>

#include "core/transform.h"

namespace glint {

// The most keys one object may move through in a frame: Embree 3's RTC_MAX_TIME_STEP_COUNT
// (accel/embree_accel.cpp asserts they agree); an animation resamples each frame's keys to fewer.
inline constexpr size_t kMaxMotionKeys = 129;

struct Quat {
  float w = 1, x = 0, y = 0, z = 0;

  static Quat fromAxisAngle(const Vec3f& axis, float degrees);
  Mat4 toMatrix() const;
  friend bool operator==(const Quat&, const Quat&) = default;
};

// Spherical linear interpolation along the shorter arc; falls back to normalised lerp when the
// two rotations nearly coincide.
Quat slerp(const Quat& a, const Quat& b, float t);

struct TrsKey {
  Vec3f scale{1, 1, 1};
  Quat rotation;
  Vec3f translation;

  Transform toTransform() const;  // translate · rotate · scale
  friend bool operator==(const TrsKey&, const TrsKey&) = default;
};

TrsKey lerp(const TrsKey& a, const TrsKey& b, float t);

// Keys k = 0 … K−1 sit at times k/(K−1). Returns the segment index and the fraction within it,
// exactly as Embree splits ray.time across time steps.
inline void motionSegment(size_t keyCount, float time, size_t& segment, float& fraction) {
  const float scaled = std::clamp(time, 0.0f, 1.0f) * static_cast<float>(keyCount - 1);
  segment = std::min(static_cast<size_t>(scaled), keyCount - 2);
  fraction = scaled - static_cast<float>(segment);
}

template <typename T>
T interpolateKeys(const std::vector<T>& keys, float time) {
  if (keys.size() == 1) return keys[0];
  size_t seg;
  float f;
  motionSegment(keys.size(), time, seg, f);
  return (1 - f) * keys[seg] + f * keys[seg + 1];
}

}  // namespace glint
