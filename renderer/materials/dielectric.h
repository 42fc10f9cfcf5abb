#pragma once
// Glass, water: a refracting interface (seed 000 §13.1, seed 001 §7). Light meeting it splits
// into a reflected part, the Fresnel reflectance R, and a refracted part 1 − R that bends by
// Snell's law; past the critical angle all of it is reflected (total internal reflection).
// Inside, Beer's law absorbs it with distance. A dielectric also has the general surface of
// surface.h (black by default), so it can carry a highlight.
// Or, with seed 002's constant coefficients (eq. 9.22, "fresnel": "none"), the interface
// transmits k_t per channel and reflects nothing of its own: the surface's k_m is k_r. Under
// total internal reflection the transmitted share is lost, as seed 001 §7 ignores it.
#include "core/rgb.h"
#include "core/vec.h"
#include "materials/beer.h"
#include "materials/fresnel.h"
#include "materials/gloss.h"
#include "materials/snell.h"

namespace glint {

struct Dielectric {
  float ior = 1.5f;
  FresnelModel fresnel = FresnelModel::Exact;
  // Seed 002's k_t: read only when `fresnel` is None (constantCoefficients()).
  Rgb kt{1, 1, 1};
  BeerMedium absorption;  // the fraction kept per unit distance inside
  float blur = 0;         // blurred translucency: the square's width, or the Phong exponent
  GlossShape blurShape = GlossShape::Square;

  bool constantCoefficients() const { return fresnel == FresnelModel::None; }
  bool blurs() const { return spreads(blurShape, blur); }

  // Light crossing from a medium of index etaI towards etaT at cosine cosI: reflected R, the
  // rest 1 − R refracted.
  float reflectance(float cosI, float etaI, float etaT) const {
    return constantCoefficients() ? 0.0f : glint::fresnel(fresnel, cosI, etaI, etaT);
  }

  // The share of light crossing at cosine cosI that the interface lets through: k_t, or 1 − R
  // (a shadow ray's factor at each interface, seed 002 §9.1).
  Rgb transmittance(float cosI, float etaI, float etaT) const {
    if (constantCoefficients()) return kt;
    const float T = 1 - glint::fresnel(fresnel, cosI, etaI, etaT);
    return {T, T, T};
  }

  // Where unit d meeting the interface (n: unit, facing against d) goes, and how much.
  struct Split {
    float R = 1;  // reflected along `reflected`; 1 − R (or k_t) along `refracted`, if it refracts
    Vec3f reflected, refracted;
    bool refracts = false;  // false under total internal reflection (R = 1)
  };
  [[gnu::always_inline]] Split split(const Vec3f& d, const Vec3f& n, float etaI, float etaT) const {
    Split s;
    s.R = reflectance(-dot(d, n), etaI, etaT);  // the share reflected
    s.reflected = reflect(d, n);
    // The rest, 1 − R, refracted; none under total internal reflection.
    s.refracts = s.R < 1 && refract(d, n, etaI / etaT, s.refracted);
    return s;
  }
};

}  // namespace glint
