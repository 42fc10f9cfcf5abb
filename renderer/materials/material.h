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

// The samples that spread a hit's lobes: the glossy mirror's and the blurred refraction's,
// each from its own dimension of the arriving ray's camera sample at the ray's depth.
struct LobeSamples {
  Vec2f gloss, blur;
};

// Whether the material draws any (lobeSamples): a surface that can be glossy (its maps vary
// the gloss below the surface's, so where a sample is drawn does not depend on the texel), or
// a blurred refraction.
inline bool drawsLobeSamples(const Material& m) {
  return m.surface.glossy() || (m.refracts() && m.dielectric.blurs());
}

// The lobe samples of material m for the ray of camera sample `key` arriving at `depth`.
inline LobeSamples lobeSamples(const Material& m, const SampleKey& key, int depth) {
  LobeSamples u{};
  if (m.surface.glossy()) u.gloss = key.get2D(dimension(Dim::Gloss, depth));
  if (m.refracts() && m.dielectric.blurs()) u.blur = key.get2D(dimension(Dim::Gloss, depth, 1));
  return u;
}

// lobeSamples(*materials[k], *keys[k], depth) into out[slot[k]] for k in [0, n), the same
// values: n rays' samples drawn side by side (Sampler::get2DAt), each pixel half's pattern made
// once for its run of rays. Drawn one at a time, a glossy hit paid for a whole stratified draw
// and a pattern.
void drawLobeSamples(const Material* const* materials, const SampleKey* const* keys,
                     const int* slot, int depth, int n, LobeSamples* out);

// The rays a hit sends on (Trace's r_r and r_t, seed 002 §9.1), for unit d arriving at the
// point (sp, at), each handed to send(direction, weight, crosses) in Trace's order: the
// surface's mirror ray (k_m), then a dielectric's reflected and refracted rays. `weight`
// multiplies the radiance the ray brings back; `crosses` says it crosses the surface into or
// out of the object. etaI and etaT are the indices on the ray's side and across (the interior
// list knows them; read only for a dielectric). A glossy mirror or a blurred refraction spreads
// its ray with the arriving ray's sample `u` (lobeSamples). (A callback rather than an array of
// rays: rays written to memory and read back at once stalled on store forwarding.)
template <class Send>
[[gnu::always_inline]] inline void forEachCoherentRay(const Material& m, const ShadingPoint& sp,
                                                      const SurfacePoint& at, const Vec3f& d,
                                                      float etaI, float etaT, const LobeSamples& u,
                                                      Send&& send) {
  // The surface's coherent reflection k_m·L(r).
  if (!at.km.isBlack()) {
    Vec3f r;
    if (mirrorDirection(d, at.n, at.gloss, m.surface.glossShape, u.gloss, r)) send(r, at.km, false);
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
    t = spread(t, g.blurShape, g.blur, u.blur);
    if (dot(t, n) >= 0) return;
  }
  const float T = 1 - split.R;
  send(t, g.constantCoefficients() ? g.kt : Rgb{T, T, T}, true);
}

// The most that the weights of the rays forEachCoherentRay sends at (sp, at) add up to in one
// channel: k_m, plus a dielectric's interface, which splits what arrives (R + (1 − R) = 1) or,
// with seed 002's constant coefficients, passes k_t. Above 1 the hit sends on more light than
// reaches it, which the integrators' cutoff must allow for (integrator/radiance.h, branchShare).
inline float coherentGain(const Material& m, const SurfacePoint& at) {
  Rgb sum = at.km;
  if (m.refracts()) sum += m.dielectric.constantCoefficients() ? m.dielectric.kt : Rgb{1, 1, 1};
  return sum.maxChannel();
}

// What the albedo AOV shows: k_d where the surface is diffuse, else k_m; 1 for a dielectric.
Rgb albedo(const Material& m, const SurfacePoint& at);

}  // namespace glint
