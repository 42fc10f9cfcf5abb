#pragma once
// Small fixed-size vectors for geometry (float, like Embree) and a few helpers on them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace glint {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
inline constexpr float kPi = 3.14159265358979323846f;

struct Vec2f {
  float x = 0, y = 0;
};

struct Vec3f {
  float x = 0, y = 0, z = 0;

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f& operator+=(const Vec3f& b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  constexpr Vec3f& operator-=(const Vec3f& b) {
    x -= b.x;
    y -= b.y;
    z -= b.z;
    return *this;
  }
  constexpr Vec3f& operator*=(float s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend constexpr bool operator==(const Vec3f&, const Vec3f&) = default;
};

constexpr Vec3f operator+(Vec3f a, const Vec3f& b) { return a += b; }
constexpr Vec3f operator-(Vec3f a, const Vec3f& b) { return a -= b; }
constexpr Vec3f operator*(Vec3f a, float s) { return a *= s; }
constexpr Vec3f operator*(float s, Vec3f a) { return a *= s; }
constexpr Vec3f operator/(const Vec3f& a, float s) { return a * (1.0f / s); }
constexpr Vec3f mul(const Vec3f& a, const Vec3f& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

constexpr float dot(const Vec3f& a, const Vec3f& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(const Vec3f& a, const Vec3f& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3f& a) { return std::sqrt(dot(a, a)); }
[[gnu::always_inline]] inline Vec3f normalize(const Vec3f& a) { return a / length(a); }
// normalize for a vector of any finite size: a surface's unnormalised normal (an edge cross
// product) squares past float's range for edges of about 10^9.5, and below its normal range for
// edges under 10^-9.5, where normalize gives 0, NaN or a few bits. Those are divided by their
// largest coordinate first; others take normalize's own operations, the same bits.
inline Vec3f normalizeAnyScale(const Vec3f& a) {
  const float squared = dot(a, a);
  if (squared >= std::numeric_limits<float>::min() && squared <= std::numeric_limits<float>::max())
      [[likely]]
    return a / std::sqrt(squared);
  const float largest = std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
  if (!(largest > 0) || !std::isfinite(largest)) return normalize(a);
  // Divided, not multiplied by 1/largest, which is infinite for a subnormal largest.
  return normalize(Vec3f{a.x / largest, a.y / largest, a.z / largest});
}
inline Vec3f abs(const Vec3f& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline float maxComponent(const Vec3f& a) { return std::max(a.x, std::max(a.y, a.z)); }
inline Vec3f min(const Vec3f& a, const Vec3f& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3f max(const Vec3f& a, const Vec3f& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline bool isFinite(const Vec3f& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// Reflect d about n (seed 000 §4.8: r = d − 2(d·n)n); n need not face d.
constexpr Vec3f reflect(const Vec3f& d, const Vec3f& n) { return d - 2.0f * dot(d, n) * n; }
constexpr Vec3f faceForward(const Vec3f& n, const Vec3f& v) { return dot(n, v) < 0 ? -n : n; }

// Writes v into dst as one 8-byte store of (x, y) and one 4-byte store of z: the widths GCC
// reads a Vec3f with (movq + movss). A load that only part of a pending store covers cannot be
// forwarded from it and waits until the stores retire (~15 cycles), so a Vec3f written
// component by component and read back soon after as a whole stalls. For results that are
// read again at once (Scene::shadingPoint's).
[[gnu::always_inline]] inline void storeWhole(Vec3f& dst, const Vec3f& v) {
  using Pair = float __attribute__((vector_size(8)));
  const Pair xy = {v.x, v.y};
  std::memcpy(&dst.x, &xy, sizeof xy);
  dst.z = v.z;
}

}  // namespace glint
