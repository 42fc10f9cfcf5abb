#pragma once
// Linear RGB radiance / reflectance triple; every optical quantity is computed per channel.
#include <cmath>

namespace glint {

struct Rgb {
  float r = 0, g = 0, b = 0;

  constexpr Rgb& operator+=(const Rgb& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr Rgb& operator*=(const Rgb& o) {
    r *= o.r;
    g *= o.g;
    b *= o.b;
    return *this;
  }
  constexpr Rgb& operator*=(float s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  friend constexpr bool operator==(const Rgb&, const Rgb&) = default;
  constexpr bool isBlack() const { return r == 0 && g == 0 && b == 0; }
  constexpr float maxChannel() const { return r > g ? (r > b ? r : b) : (g > b ? g : b); }
  bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator+(Rgb a, const Rgb& b) { return a += b; }
constexpr Rgb operator*(Rgb a, const Rgb& b) { return a *= b; }
constexpr Rgb operator*(Rgb a, float s) { return a *= s; }
constexpr Rgb operator*(float s, Rgb a) { return a *= s; }

}  // namespace glint
