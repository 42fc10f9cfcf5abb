#pragma once
// Absorption inside a dielectric (Beer's law, seed 000 §13.1): light travelling a distance s
// through a medium that keeps a fraction a per unit distance keeps a^s = exp(ln(a)·s), per
// channel. a = 1 transmits fully even for s = ∞, and a = 0 blocks fully even for s = 0⁺, so
// 0·∞ never reaches exp and no NaN comes out.
#include <cmath>

#include "core/rgb.h"

namespace glint {

// lnA: ln(a), which a medium takes once (BeerMedium) instead of per segment.
inline float beerChannel(float a, float s, float lnA) {
  if (a >= 1 || s <= 0) return 1;
  if (a <= 0 || std::isinf(s)) return 0;
  return std::exp(lnA * s);
}
// ln(a) where beerChannel reads it, a in (0, 1); 0 elsewhere, where it is never read.
inline float lnAttenuation(float a) { return a > 0 && a < 1 ? std::log(a) : 0; }
inline float beerChannel(float a, float s) { return beerChannel(a, s, lnAttenuation(a)); }
inline Rgb beer(const Rgb& a, float s) {
  return {beerChannel(a.r, s), beerChannel(a.g, s), beerChannel(a.b, s)};
}

// A medium's attenuation per unit distance with its logarithms taken once: transmittance(s)
// is beer(a, s), bit for bit.
class BeerMedium {
 public:
  BeerMedium() = default;
  explicit BeerMedium(const Rgb& attenuation)
      : a_(attenuation), lnA_{lnAttenuation(a_.r), lnAttenuation(a_.g), lnAttenuation(a_.b)} {}
  const Rgb& attenuation() const { return a_; }
  bool absorbs() const { return !(a_ == Rgb{1, 1, 1}); }
  Rgb transmittance(float s) const {
    return {beerChannel(a_.r, s, lnA_.r), beerChannel(a_.g, s, lnA_.g),
            beerChannel(a_.b, s, lnA_.b)};
  }

 private:
  Rgb a_{1, 1, 1}, lnA_{0, 0, 0};
};

}  // namespace glint
