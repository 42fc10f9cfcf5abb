#pragma once
// A material: the general surface of seed 002 §9.1 (surface.h) that every material has, and for
// a dielectric a refracting interface (dielectric.h). The scene's three material types are this
// one model with different defaults (docs/scene-format.md):
//   phong       k_d 0.5; no highlight, no mirror
//   mirror      k_m 1; everything else black
//   dielectric  an interface of index 1.5; the surface black
// and for all three k_a = k_d unless given.
// forEachCoherentRay() is the one place where what a material is decides what happens at a hit.
#include <string>

#include "core/sampler.h"
#include "geometry/shading_point.h"
#include "materials/cutout.h"
#include "materials/dielectric.h"
#include "materials/surface.h"

namespace glint {

enum class MaterialKind { Phong, Mirror, Dielectric };

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::Phong;
  Surface surface;
  Dielectric dielectric;  // read only when kind is Dielectric
  Cutout cutout;          // holes in the surface; read by the intersection backends

  bool refracts() const { return kind == MaterialKind::Dielectric; }
};

// The defaults of each kind, above.
Material defaultMaterial(MaterialKind kind);

// The most rays forEachCoherentRay sends: a dielectric's surface mirror, and its interface's
// reflection and refraction.
inline constexpr int kMaxCoherentRays = 3;

// The rays a hit sends on (Trace's r_r and r_t, seed 002 §9.1), for unit d arriving at the
// point (sp, at), each handed to send(direction, weight, crosses) in Trace's order: the
// surface's mirror ray (k_m), then a dielectric's reflected and refracted rays. `weight`
// multiplies the radiance the ray brings back; `crosses` says it crosses the surface into or
// out of the object. etaI and etaT are the indices on the ray's side and across (the interior
// list knows them; read only for a dielectric). A glossy mirror or a blurred refraction draws
// its sample from `key` at `depth`, the depth of the arriving ray. (A callback rather than an
// array of rays: rays written to memory and read back at once stalled on store forwarding.)
template <class Send>
[[gnu::always_inline]] inline void forEachCoherentRay(const Material& m, const ShadingPoint& sp,
                                                      const SurfacePoint& at, const Vec3f& d,
                                                      float etaI, float etaT, const SampleKey& key,
                                                      int depth, Send&& send) {
  // The surface's coherent reflection k_m·L(r).
  if (!at.km.isBlack()) {
    // The sample is drawn wherever the surface can be glossy (its maps vary at.gloss below
    // s.gloss): where it is drawn does not depend on the texel.
    const Surface& s = m.surface;
    const Vec2f u = s.glossy() ? key.get2D(dimension(Dim::Gloss, depth)) : Vec2f{};
    Vec3f r;
    if (mirrorDirection(d, at.n, at.gloss, s.glossShape, u, r)) send(r, at.km, false);
  }
  if (!m.refracts()) return;
  // The interface: the normal is the geometric one turned against the ray, never the shading
  // normal, so that which side is which is decided where the medium boundary really is.
  const Dielectric& g = m.dielectric;
  const Vec3f n = dot(d, sp.ng) < 0 ? sp.ng : -sp.ng;
  const Dielectric::Split split = g.split(d, n, etaI, etaT);
  // With seed 002's constant coefficients the interface reflects nothing of its own.
  if (!g.constantCoefficients()) send(split.reflected, Rgb{split.R, split.R, split.R}, false);
  if (!split.refracts) return;
  Vec3f t = split.refracted;
  if (g.blurs()) {
    // Blurred translucency (seed 002 §9.3): t spread by the same lobes as gloss; a ray that
    // ends up back on the incoming side returns black.
    t = spread(t, g.blurShape, g.blur, key.get2D(dimension(Dim::Gloss, depth, 1)));
    if (dot(t, n) >= 0) return;
  }
  const float T = 1 - split.R;
  send(t, g.constantCoefficients() ? g.kt : Rgb{T, T, T}, true);
}

// What the albedo AOV shows: k_d where the surface is diffuse, else k_m; 1 for a dielectric.
Rgb albedo(const Material& m, const SurfacePoint& at);

}  // namespace glint
