#pragma once
// How much light a dielectric interface reflects (seed 000 §13.1), as a function of the cosine
// of incidence and the indices of refraction on both sides. Cosines are clamped to [0, 1] and
// total internal reflection is explicit, so every input gives a reflectance in [0, 1].
#include <algorithm>
#include <cmath>

namespace glint {

// None: no Fresnel law at all; the interface's constant coefficients stand in for it
// (materials/dielectric.h), and fresnel() is never asked for it.
enum class FresnelModel { Exact, Schlick, None };

// The exact unpolarised Fresnel reflectance (the mean of the s and p polarisations) for light
// arriving at cosine cosI from a medium of index etaI into one of index etaT. 1 under total
// internal reflection.
inline float fresnelDielectric(float cosI, float etaI, float etaT) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  const float sin2T = (etaI / etaT) * (etaI / etaT) * std::max(0.0f, 1 - cosI * cosI);
  if (sin2T >= 1) return 1;
  const float cosT = std::sqrt(1 - sin2T);
  const float rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  const float rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
  return std::clamp(0.5f * (rs * rs + rp * rp), 0.0f, 1.0f);
}

// Schlick's approximation R₀ + (1 − R₀)(1 − cosθ)⁵ (seed 000 §13.1), with the cosine taken on
// the less dense side, where it is valid.
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

inline float fresnel(FresnelModel model, float cosI, float etaI, float etaT) {
  return model == FresnelModel::Exact ? fresnelDielectric(cosI, etaI, etaT)
                                      : fresnelSchlick(cosI, etaI, etaT);
}

}  // namespace glint
