#include "lights/light.h"

#include <cmath>

#include "core/sampling.h"

namespace glint {

namespace {

// Orthonormal tangents of unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void tangents(const Vec3f& n, Vec3f& t, Vec3f& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

LightSample fromPoint(const Vec3f& p, const Vec3f& y, const Rgb& intensity, Falloff falloff,
                      Emission emission, const Vec3f& lightNormal, float area) {
  const Vec3f toLight = y - p;
  const float dist2 = dot(toLight, toLight);
  LightSample s;
  s.wi = toLight / std::sqrt(dist2);
  s.target = y;
  if (emission == Emission::Radiance) {
    // E = ∫ L cosθ_y / r² dA estimated with one uniform point: L·max(0, cosθ_y)·A / r².
    const float cosY = std::max(0.0f, -dot(lightNormal, s.wi));
    s.intensity = intensity * (cosY * area / dist2);
  } else {
    s.intensity = falloff == Falloff::InverseSquare ? intensity * (1.0f / dist2) : intensity;
  }
  return s;
}

}  // namespace

int lightSampleCount(const Light& light) {
  if (const auto* q = std::get_if<QuadLight>(&light)) return q->samples;
  if (const auto* d = std::get_if<DiskLight>(&light)) return d->samples;
  return 1;
}

LightSample sampleLight(const Light& light, const Vec3f& p, Vec2f u) {
  if (const auto* pl = std::get_if<PointLight>(&light))
    return fromPoint(p, pl->position, pl->intensity, pl->falloff, Emission::Seed, {}, 0);
  if (const auto* q = std::get_if<QuadLight>(&light)) {
    const Vec3f n = cross(q->edge1, q->edge2);
    const float area = length(n);
    return fromPoint(p, q->corner + u.x * q->edge1 + u.y * q->edge2, q->intensity, q->falloff,
                     q->emission, n / area, area);
  }
  if (const auto* d = std::get_if<DiskLight>(&light)) {
    Vec3f t, b;
    tangents(d->normal, t, b);
    const Vec2f disk = squareToDiskConcentric(u);
    const Vec3f y = d->center + d->radius * (disk.x * t + disk.y * b);
    return fromPoint(p, y, d->intensity, d->falloff, d->emission, d->normal,
                     kPi * d->radius * d->radius);
  }
  const auto& dl = std::get<DirectionalLight>(light);
  LightSample s;
  s.wi = -dl.direction;
  s.target = p + s.wi;
  s.atInfinity = true;
  s.intensity = dl.intensity;
  return s;
}

}  // namespace glint
