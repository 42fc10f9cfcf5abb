#pragma once
// An accelerator that answers with a primary backend and checks every query against others,
// hit by hit: what `glint validate` runs the renderer through. Not thread-safe: validation
// renders on one thread so that its statistics and first disagreements are reproducible.
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/bounds.h"

namespace glint {

struct CrossCheckStats {
  uint64_t rays = 0, hitAgree = 0, primAgree = 0;  // closest-hit queries
  uint64_t occlusionRays = 0, occlusionAgree = 0;  // any-hit queries
  uint64_t originTies = 0;   // queries that agree only as a hit at the origin (kOriginTolerance)
  std::vector<float> relDt;  // |Δt|/max(1, t) where both hit
  std::vector<std::string> firstDisagreements;  // reproducible one-liners

  double hitAgreement() const { return rays ? double(hitAgree) / double(rays) : 1; }
  double primAgreement() const { return rays ? double(primAgree) / double(rays) : 1; }
  double occlusionAgreement() const {
    return occlusionRays ? double(occlusionAgree) / double(occlusionRays) : 1;
  }
  float maxRelDt() const;
  float quantileRelDt(double q) const;
};

class CrossCheck final : public Accelerator {
 public:
  static constexpr size_t kKeptDisagreements = 10;
  // Two hits on different primitives whose t agree this closely are a tie (a shared edge or a
  // coincident face), not a disagreement.
  static constexpr float kTieTolerance = 1e-5f;
  // A hit this close to the ray's origin, relative to the origin's largest coordinate (at least
  // 1), against a miss or a farther hit is a tie too, counted apart (originTies): a ray that
  // starts on a surface hits it at t = 0 ± rounding, and Embree's and Glint's triangle tests
  // round differently (random rays start on the plane of a flat scene once in ~4000). 2⁻²⁰ is
  // eight float steps of that coordinate; far from the origin, where every hit on a small
  // shape is that close, callers bound how many ties they accept.
  static constexpr float kOriginTolerance = 0x1p-20f;

  CrossCheck(const Accelerator& primary, std::vector<const Accelerator*> others)
      : primary_(primary), others_(std::move(others)) {}

  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  std::string_view name() const override { return "cross-check"; }

  const CrossCheckStats& stats() const { return stats_; }

 private:
  void record(const std::string& line) const;
  // Whether `hit` lies at `ray`'s origin, within kOriginTolerance.
  static bool atOrigin(const Ray& ray, const Hit& hit);

  const Accelerator& primary_;
  std::vector<const Accelerator*> others_;
  mutable CrossCheckStats stats_;
};

// A ray as a one-line, exactly reproducible string (hex floats): "ox oy oz dx dy dz tmin tmax
// time", and back. parseRay returns false on malformed input.
std::string formatRay(const Ray& ray);
bool parseRay(const std::string& text, Ray& ray);
// Why Embree must not be given `ray` (its debug checks abort the process), or "" if it may:
// origin and direction finite and within ±kMaxRayOrigin (core/ray.h), direction not zero,
// 0 ≤ tMin ≤ tMax (tMax may be infinite), time in [0, 1].
std::string rayProblem(const Ray& ray);
std::string formatHit(const Hit& hit);

class Scene;
// Where random rays start: the scene's bounds grown by 10 %, kept within ±1e18, where Embree
// takes ray origins (beyond 1.8e18 its checks abort; a scene may hold geometry farther out).
Bounds3f randomRayOrigins(const Scene& scene);

// Casts `count` random rays through `accel` (closest hit and occlusion each): origins uniform in
// the scene's bounds grown by 10 %, directions uniform on the sphere, times uniform in [0, 1].
void castRandomRays(const Scene& scene, const Accelerator& accel, int count, uint64_t seed);

}  // namespace glint
