#pragma once
// The general surface of seed 002 §9.1, which every material has. Light leaving a surface point
// towards the viewer is the sum of
//   - its own emission k_e and the ambient light it reflects, k_a·I_a   (ambientAndEmission)
//   - per light source, the diffuse and specular light it reflects      (reflectedLight)
//     k_d·I·max(0, n·l) + k_s·I·max(0, n·h)^p   (Blinn-Phong; Phong: max(0, r·v)^p)
//   - coherently reflected light k_m·L(r), r the mirror direction,      (mirrorDirection)
//     spread by a glossy surface over a square of width `gloss` or a Phong lobe cos^gloss
// each per RGB channel. The seeds' coefficients multiply intensities directly: there is no 1/π,
// so a white Lambert surface under a unit light at normal incidence reads 1 (docs/shading.md).
// Surfaces are two-sided: the shading normal is turned towards the viewer.
#include <cmath>
#include <memory>

#include "core/affine.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "geometry/shading_point.h"
#include "materials/gloss.h"
#include "materials/normal_map.h"
#include "materials/surface_maps.h"
#include "materials/texture.h"

namespace glint {

enum class SpecularModel { BlinnPhong, Phong };

// k_e is seen from both sides, or (a one-sided emitter: an area light in radiance mode) only
// from the side its geometric normal points to.
enum class EmissionSides { Both, Front };

struct Surface {
  ColorTexture ka, kd, ks, km, ke;
  // ka is kd (the scene gave no "ka"): the ambient term reuses the diffuse colour already
  // looked up at the point instead of evaluating the same texture twice.
  bool ambientFollowsDiffuse = false;
  float exponent = 32;
  SpecularModel specularModel = SpecularModel::BlinnPhong;
  float gloss = 0;  // the square's width, or the Phong lobe's exponent
  GlossShape glossShape = GlossShape::Square;
  EmissionSides emissionSides = EmissionSides::Both;
  // Normal and bump maps; null for a surface without (nearly all): then no hit or light sample
  // reads them.
  std::shared_ptr<const ShadingMaps> normalMaps;
  // Quantities that vary by image data where no slot holds them (materials/surface_maps.h);
  // null for nearly every surface. With a metallic-roughness map, km, exponent and gloss hold
  // their largest values (b times metallicFactor, roughnessFactor's gloss), which the scene's
  // Features and the sampler's dimensions are decided by.
  std::shared_ptr<const SurfaceMaps> maps;

  // Whether AccLightSource's loop over the lights can add anything (k_d or k_s not black).
  [[gnu::always_inline]] bool reflectsLights() const { return !kd.isBlack() || !ks.isBlack(); }
  [[gnu::always_inline]] bool reflectsCoherently() const { return !km.isBlack(); }
  [[gnu::always_inline]] bool glossy() const { return spreads(glossShape, gloss); }
  [[gnu::always_inline]] bool emits() const { return !ke.isBlack(); }
};

// A surface at one hit, seen from one direction: its textures looked up there, once.
struct SurfacePoint {
  Vec3f n;          // unit shading normal, on the viewer's side (bent by the surface's maps)
  Vec3f wo;         // unit, towards the viewer
  float footprint;  // the width of the pixel's footprint here (image textures filter over it)
  Rgb kd, ks, km;
  float exponent, gloss;  // the surface's, or its maps' here
};

// lookUp's part for a surface with a metallic-roughness map: at.kd holds the base colour, at.ks
// the dielectric's highlight; they, km, exponent and gloss become the point's.
void splitMetal(const SurfaceMaps& maps, const ShadingPoint& sp, SurfacePoint& at);
// What the ambient term is multiplied by at the point: 1 without an occlusion map.
float ambientOcclusion(const SurfaceMaps& maps, const ShadingPoint& sp, const SurfacePoint& at);

// Always inlined (like forEachCoherentRay), and written field by field into the caller's `at`:
// returned from out of line, or built on the stack and copied into the pending list, the point
// was read back in pieces that straddled its fields' stores (a store-forwarding stall at every
// shaded hit).
// `footprint`: the width of the pixel's footprint at the point (integrator/footprint.h).
[[gnu::always_inline]] inline void lookUp(const Surface& s, const ShadingPoint& sp, const Vec3f& wo,
                                          float footprint, const Vec3d& worldOrigin,
                                          SurfacePoint& at) {
  at.n = sp.shadingNormalFacing(wo);
  if (s.normalMaps) [[unlikely]] {
    const Vec3f mapped = mappedNormal(*s.normalMaps, sp, wo, footprint);
    at.n = dot(sp.ng, wo) < 0 ? -mapped : mapped;  // the viewer's side, as shadingNormalFacing
  }
  at.wo = wo;
  at.footprint = footprint;
  at.kd = s.kd.eval(sp, wo, footprint, worldOrigin);
  at.ks = s.ks.eval(sp, wo, footprint, worldOrigin);
  at.exponent = s.exponent;
  at.gloss = s.gloss;
  if (s.maps && s.maps->metallicRoughness) [[unlikely]] {
    splitMetal(*s.maps, sp, at);
    return;
  }
  at.km = s.km.eval(sp, wo, footprint, worldOrigin);
}
[[gnu::always_inline]] inline SurfacePoint lookUp(const Surface& s, const ShadingPoint& sp,
                                                  const Vec3f& wo, float footprint,
                                                  const Vec3d& worldOrigin) {
  SurfacePoint at;
  lookUp(s, sp, wo, footprint, worldOrigin, at);
  return at;
}

// AccLightSource's first line: c = ambient intensity + own emission (seed 002 §9.1), with
// `ambientLight` the scene's I_a.
[[gnu::always_inline]] inline Rgb ambientAndEmission(const Surface& s, const SurfacePoint& at,
                                                     const ShadingPoint& sp,
                                                     const Rgb& ambientLight,
                                                     const Vec3d& worldOrigin) {
  Rgb ka = s.ambientFollowsDiffuse ? at.kd : s.ka.eval(sp, at.wo, at.footprint, worldOrigin);
  if (s.maps) [[unlikely]]
    ka = ka * ambientOcclusion(*s.maps, sp, at);
  Rgb c = ka * ambientLight;
  if (s.emits() && (s.emissionSides == EmissionSides::Both || dot(at.wo, sp.ng) > 0))
    c += s.ke.eval(sp, at.wo, at.footprint, worldOrigin);
  return c;
}

// cosine^exponent of the highlight's lobe, cosine in [0, 1]. Scenes nearly always give whole
// exponents; those are raised by repeated squaring, a handful of multiplies instead of powf's
// logarithm and exponential. Squaring doubles the relative error it is given, so the result is
// within about 2·exponent float roundings of the exact power: the same order as the change one
// ulp of the cosine makes to cosine^exponent.
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

// The highlight's lobe for light arriving along unit wi (seed 000 eq. 4.4, seed 001 §5.3):
// max(0, n·h)^p with h halfway between wi and wo (Blinn-Phong), or max(0, r·wo)^p with r the
// mirror image of the light direction (Phong).
[[gnu::always_inline]] inline float highlightLobe(const Surface& s, const SurfacePoint& at,
                                                  const Vec3f& wi) {
  const float cosine = s.specularModel == SpecularModel::BlinnPhong
                           ? dot(at.n, normalize(wi + at.wo))
                           : dot(reflect(-wi, at.n), at.wo);
  return specularPower(std::max(0.0f, cosine), at.exponent);
}

// Whether light arriving along unit wi reaches the side of the surface the viewer sees: from
// behind, a light adds nothing, and no shadow ray need be traced for it.
[[gnu::always_inline]] inline bool facesLight(const SurfacePoint& at, const Vec3f& wi) {
  return dot(at.n, wi) > 0;
}

// What the surface reflects towards the viewer of a light of unit intensity arriving along
// unit wi: diffuse plus the highlight. Black for light from behind the surface. Under a normal
// or bump map, faded by the bump shadowing term (materials/normal_map.h) so that the bent
// normal brings back no shadow terminator: `sp`, the point `at` was looked up at, has the
// unmapped normal.
[[gnu::always_inline]] inline Rgb reflectedLight(const Surface& s, const ShadingPoint& sp,
                                                 const SurfacePoint& at, const Vec3f& wi) {
  const float cosL = dot(at.n, wi);
  if (cosL <= 0) return {};
  Rgb f = at.kd * cosL;                                         // diffuse: Lambert's cosine
  if (!at.ks.isBlack()) f += at.ks * highlightLobe(s, at, wi);  // the highlight
  if (s.normalMaps) [[unlikely]]
    f = f * bumpShadowing(sp.shadingNormalFacing(at.wo), at.n, wi);
  return f;
}

// The direction coherent reflection leaves in, for unit d arriving at a point whose normal n
// faces against d: the mirror direction r = d − 2(d·n)n (seed 000 §4.8), spread by the lobe of
// `shape` sized `gloss` with the sample u for a glossy surface. False where a spread ray would
// leave below the surface (it returns black).
[[gnu::always_inline]] inline bool mirrorDirection(const Vec3f& d, const Vec3f& n, float gloss,
                                                   GlossShape shape, Vec2f u, Vec3f& r) {
  r = reflect(d, n);
  if (!spreads(shape, gloss)) return true;
  r = spread(r, shape, gloss, u);
  return dot(r, n) > 0;
}

}  // namespace glint
