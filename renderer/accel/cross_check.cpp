#include "accel/cross_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/hash.h"
#include "scene/scene.h"

namespace glint {

float CrossCheckStats::maxRelDt() const {
  return relDt.empty() ? 0.0f : *std::max_element(relDt.begin(), relDt.end());
}

float CrossCheckStats::quantileRelDt(double q) const {
  if (relDt.empty()) return 0;
  std::vector<float> v = relDt;
  const auto k = static_cast<size_t>(std::min(double(v.size() - 1), q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

std::string formatRay(const Ray& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%a %a %a %a %a %a %a %a %a", double(r.o.x), double(r.o.y),
                double(r.o.z), double(r.d.x), double(r.d.y), double(r.d.z), double(r.tMin),
                double(r.tMax), double(r.time));
  return buf;
}

std::string rayProblem(const Ray& r) {
  const auto finite = [](const Vec3f& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (!finite(r.o)) return "the origin is not finite";
  // Embree asserts (an abort) on origins past about 1.8e18; random rays keep within kMaxOrigin
  // for the same reason (randomRayOrigins).
  if (!withinRayRange(r.o))
    return "the origin lies more than 1e18 from 0 along an axis (Embree's limit)";
  if (!finite(r.d)) return "the direction is not finite";
  if (!withinRayRange(r.d))
    return "the direction has a component past 1e18 (Embree's limit; its length does not matter)";
  if (r.d.x == 0 && r.d.y == 0 && r.d.z == 0) return "the direction is zero";
  if (!(r.tMin >= 0)) return "tmin must be ≥ 0";
  if (!(r.tMax >= r.tMin)) return "tmax must be ≥ tmin";
  if (!(r.time >= 0 && r.time <= 1)) return "time must be in [0, 1]";
  return {};
}

bool parseRay(const std::string& text, Ray& r) {
  std::istringstream in(text);
  double v[9];
  for (double& x : v) {
    std::string tok;
    if (!(in >> tok)) return false;
    char* end = nullptr;
    x = std::strtod(tok.c_str(), &end);
    if (*end != 0) return false;
  }
  std::string extra;
  if (in >> extra) return false;
  r.o = {float(v[0]), float(v[1]), float(v[2])};
  r.d = {float(v[3]), float(v[4]), float(v[5])};
  r.tMin = float(v[6]);
  r.tMax = float(v[7]);
  r.time = float(v[8]);
  return true;
}

std::string formatHit(const Hit& h) {
  if (!h) return "miss";
  char buf[160];
  std::snprintf(buf, sizeof buf, "hit geom %u prim %u inst %s t %.9g", h.geomId, h.primId,
                h.instId == kInvalidId ? "-" : std::to_string(h.instId).c_str(), double(h.t));
  return buf;
}

void CrossCheck::record(const std::string& line) const {
  if (stats_.firstDisagreements.size() < kKeptDisagreements)
    stats_.firstDisagreements.push_back(line);
}

bool CrossCheck::atOrigin(const Ray& ray, const Hit& hit) {
  const float scale = std::max({1.0f, std::fabs(ray.o.x), std::fabs(ray.o.y), std::fabs(ray.o.z)});
  return hit && hit.t <= kOriginTolerance * scale;
}

Hit CrossCheck::intersect(const Ray& ray) const {
  const Hit a = primary_.intersect(ray);
  for (const Accelerator* other : others_) {
    const Hit b = other->intersect(ray);
    ++stats_.rays;
    bool hitAgree = bool(a) == bool(b), primAgree = hitAgree;
    const float rel = a && b ? std::fabs(a.t - b.t) / std::max(1.0f, a.t) : 0.0f;
    if (a && b)
      primAgree = (a.geomId == b.geomId && a.primId == b.primId && a.instId == b.instId) ||
                  rel <= kTieTolerance;
    if (!primAgree && (atOrigin(ray, a) || atOrigin(ray, b))) {
      hitAgree = primAgree = true;
      ++stats_.originTies;  // not a |Δt| of one surface: left out of relDt
    } else if (a && b) {
      stats_.relDt.push_back(rel);
    }
    stats_.hitAgree += hitAgree;
    stats_.primAgree += primAgree;
    if (!primAgree)
      record("--ray \"" + formatRay(ray) + "\"  # " + std::string(primary_.name()) + ": " +
             formatHit(a) + "; " + std::string(other->name()) + ": " + formatHit(b));
  }
  return a;
}

bool CrossCheck::occluded(const Ray& ray) const {
  const bool a = primary_.occluded(ray);
  for (const Accelerator* other : others_) {
    const bool b = other->occluded(ray);
    ++stats_.occlusionRays;
    // The backend that says occluded: is its closest hit at the origin (a tie, as above)?
    const bool tie = a != b && atOrigin(ray, (a ? primary_ : *other).intersect(ray));
    const bool agree = a == b || tie;
    stats_.occlusionAgree += agree;
    stats_.originTies += tie;
    if (!agree)
      record("--ray \"" + formatRay(ray) + "\" --occluded  # " + std::string(primary_.name()) +
             ": " + (a ? "occluded" : "clear") + "; " + std::string(other->name()) + ": " +
             (b ? "occluded" : "clear"));
  }
  return a;
}

Bounds3f randomRayOrigins(const Scene& scene) {
  Bounds3f b = scene.worldBounds();
  if (b.empty()) b = {{-1, -1, -1}, {1, 1, 1}};
  const Vec3f margin = 0.1f * b.diagonal() + Vec3f{1e-3f, 1e-3f, 1e-3f};
  const Vec3f range{kMaxRayOrigin, kMaxRayOrigin, kMaxRayOrigin};
  return {max(b.lo - margin, -range), min(b.hi + margin, range)};
}

void castRandomRays(const Scene& scene, const Accelerator& accel, int count, uint64_t seed) {
  const Bounds3f b = randomRayOrigins(scene);
  for (int i = 0; i < count; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(seed, 0x7a11da7e, i, k)); };
    Ray r;
    r.o = b.lo + mul(b.diagonal(), Vec3f{u(0), u(1), u(2)});
    const float z = 1 - 2 * u(3), phi = 2 * kPi * u(4);
    const float s = std::sqrt(std::max(0.0f, 1 - z * z));
    r.d = {s * std::cos(phi), s * std::sin(phi), z};
    r.time = u(5);
    accel.intersect(r);
    accel.occluded(r);
  }
}

}  // namespace glint
