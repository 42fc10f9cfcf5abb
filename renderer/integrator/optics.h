#pragma once
// Dielectric optics of seed 000 §13.1 and seed 001 §7, with every cosine clamped and total
// internal reflection explicit, so no NaN can come out for any input direction; and the power
// of the Phong lobe.
#include <algorithm>
#include <cmath>

#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

// cosine^exponent of the Phong and Blinn-Phong lobes (seed 000 eq. 4.4), cosine in [0, 1].
// Scenes nearly always give whole exponents; those are raised by repeated squaring, a handful
// of multiplies instead of powf's logarithm and exponential. Squaring doubles the relative error
// it is given, so the result is within about 2·exponent float roundings of the exact power: the
// same order as the change one ulp of the cosine makes to cosine^exponent.
inline float specularPower(float cosine, float exponent) {
  // Whole: the integer conversion is exact in that range (std::floor is a libm call here).
  if (!(exponent >= 0 && exponent <= 65535 &&
        static_cast<float>(static_cast<unsigned>(exponent)) == exponent))
    return std::pow(cosine, exponent);
  float result = 1, base = cosine;
  for (auto n = static_cast<unsigned>(exponent); n != 0; n >>= 1) {
    if (n & 1) result *= base;
    base *= base;
  }
  return result;
}

// Exact unpolarised Fresnel reflectance for light arriving at cosine cosI (clamped to [0, 1])
// from a medium of index etaI into one of index etaT. Returns 1 under total internal reflection.
inline float fresnelDielectric(float cosI, float etaI, float etaT) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  const float sin2T = (etaI / etaT) * (etaI / etaT) * std::max(0.0f, 1 - cosI * cosI);
  if (sin2T >= 1) return 1;
  const float cosT = std::sqrt(1 - sin2T);
  const float rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  const float rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
  return std::clamp(0.5f * (rs * rs + rp * rp), 0.0f, 1.0f);
}

// Schlick's approximation (seed 000 §13.1), with the cosine taken on the less dense side.
inline float fresnelSchlick(float cosI, float etaI, float etaT) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  float cosine = cosI;
  if (etaI > etaT) {
    const float sin2T = (etaI / etaT) * (etaI / etaT) * std::max(0.0f, 1 - cosI * cosI);
    if (sin2T >= 1) return 1;
    cosine = std::sqrt(1 - sin2T);
  }
  const float r0 = ((etaT - etaI) / (etaT + etaI)) * ((etaT - etaI) / (etaT + etaI));
  const float m = 1 - cosine;
  return r0 + (1 - r0) * m * m * m * m * m;
}

// Refracts unit d through a surface with unit normal n facing against d (dot(d, n) ≤ 0),
// eta = etaI / etaT (seed 001 §7). Returns false under total internal reflection.
inline bool refract(const Vec3f& d, const Vec3f& n, float eta, Vec3f& t) {
  const float cosI = std::clamp(-dot(d, n), 0.0f, 1.0f);
  const float sin2T = eta * eta * std::max(0.0f, 1 - cosI * cosI);
  if (sin2T >= 1) return false;
  const float cosT = std::sqrt(1 - sin2T);
  t = normalize(eta * d + (eta * cosI - cosT) * n);
  return true;
}

// Beer's law I(s) = I(0)·exp(ln(a)·s) per channel; a = 1 transmits fully even for s = ∞, and
// a = 0 blocks fully even for s = 0⁺, so 0·∞ never reaches exp. lnA: ln(a), which a medium
// can take once (BeerMedium) instead of per segment.
inline float beerChannel(float a, float s, float lnA) {
  if (a >= 1 || s <= 0) return 1;
  if (a <= 0 || std::isinf(s)) return 0;
  return std::exp(lnA * s);
}
// ln(a) where beerChannel uses it, a in (0, 1); 0 elsewhere, where it is never read.
inline float lnAttenuation(float a) { return a > 0 && a < 1 ? std::log(a) : 0; }
inline float beerChannel(float a, float s) { return beerChannel(a, s, lnAttenuation(a)); }
inline Rgb beer(const Rgb& a, float s) {
  return {beerChannel(a.r, s), beerChannel(a.g, s), beerChannel(a.b, s)};
}

// A medium's attenuation per unit distance with its logarithms taken once: transmittance(s)
// is beer(a, s), bit for bit.
struct BeerMedium {
  BeerMedium() = default;
  explicit BeerMedium(const Rgb& attenuation)
      : a(attenuation), lnA{lnAttenuation(a.r), lnAttenuation(a.g), lnAttenuation(a.b)} {}
  Rgb transmittance(float s) const {
    return {beerChannel(a.r, s, lnA.r), beerChannel(a.g, s, lnA.g), beerChannel(a.b, s, lnA.b)};
  }

 private:
  Rgb a{1, 1, 1}, lnA{0, 0, 0};
};

}  // namespace glint
