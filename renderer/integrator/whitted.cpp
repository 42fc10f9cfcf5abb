#include "integrator/whitted.h"

#include <cmath>

#include "integrator/optics.h"

namespace glint {

Radiance WhittedIntegrator::trace(const Ray& cameraRay, RayCounters& counters) const {
  ++counters.camera;
  bool hit = false;
  Radiance r;
  r.L = Li(cameraRay, 0, Rgb{1, 1, 1}, nullptr, counters, &hit);
  r.alpha = hit ? 1.0f : 0.0f;
  return r;
}

Rgb WhittedIntegrator::Li(const Ray& ray, int depth, const Rgb& throughput,
                          const DielectricMaterial* medium, RayCounters& counters,
                          bool* hitSomething) const {
  const Hit hit = accel_.intersect(ray);
  const float travelled = hit.t * length(ray.d);
  const Rgb absorbed = medium ? beer(medium->attenuation, travelled) : Rgb{1, 1, 1};
  if (!hit) return scene_.render.background * absorbed;
  if (hitSomething) *hitSomething = true;

  const ShadingPoint sp = scene_.shadingPoint(ray, hit);
  const Material& material = scene_.materials[sp.materialId].material;
  const Vec3f wo = normalize(-ray.d);
  Rgb L;
  if (const auto* phong = std::get_if<PhongMaterial>(&material)) {
    L = shadePhong(*phong, sp, wo, ray.time, counters);
    L += reflectRay(phong->km, sp, ray, depth, throughput, medium, counters);
  } else if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
    L = reflectRay(mirror->km, sp, ray, depth, throughput, medium, counters);
  } else {
    L = shadeDielectric(std::get<DielectricMaterial>(material), sp, ray, depth, throughput,
                        counters);
  }
  return L * absorbed;
}

Rgb WhittedIntegrator::shadePhong(const PhongMaterial& m, const ShadingPoint& sp, const Vec3f& wo,
                                  float time, RayCounters& counters) const {
  // Seed 000 eq. 4.4 / seed 001 §5: surfaces are two-sided, so the normal faces the viewer.
  const Vec3f n = faceForward(sp.ns, wo);
  const Rgb kd = m.kd.eval(sp.p);
  Rgb L = m.ka.eval(sp.p) * scene_.render.ambient;
  for (const Light& light : scene_.lights) {
    const LightSample ls = sampleLight(light, sp.p);
    const float cosL = dot(n, ls.wi);
    if (cosL <= 0) continue;
    ++counters.shadow;
    Ray shadow = ls.atInfinity ? spawnRay(sp, ls.wi, time) : spawnRayTo(sp, ls.target, time);
    if (accel_.occluded(shadow)) continue;
    Rgb f = kd * cosL;
    if (!m.ks.isBlack()) {
      float spec;
      if (m.specularModel == SpecularModel::BlinnPhong) {
        spec = std::max(0.0f, dot(n, normalize(ls.wi + wo)));
      } else {
        spec = std::max(0.0f, dot(reflect(-ls.wi, n), wo));
      }
      f += m.ks * std::pow(spec, m.exponent);
    }
    L += f * ls.intensity;
  }
  return L;
}

Rgb WhittedIntegrator::reflectRay(const Rgb& km, const ShadingPoint& sp, const Ray& ray, int depth,
                                  const Rgb& throughput, const DielectricMaterial* medium,
                                  RayCounters& counters) const {
  // Seed 000 §4.8: no ray when k_m is black, past the depth limit, or when the branch's
  // throughput is negligible.
  const Rgb weight = throughput * km;
  if (km.isBlack() || depth + 1 > scene_.render.maxDepth || weight.maxChannel() < kMinThroughput)
    return {};
  const Vec3f d = normalize(ray.d);
  const Vec3f n = faceForward(sp.ns, -d);
  ++counters.reflection;
  return km * Li(spawnRay(sp, reflect(d, n), ray.time), depth + 1, weight, medium, counters);
}

Rgb WhittedIntegrator::shadeDielectric(const DielectricMaterial& m, const ShadingPoint& sp,
                                       const Ray& ray, int depth, const Rgb& throughput,
                                       RayCounters& counters) const {
  if (depth + 1 > scene_.render.maxDepth) return {};
  const Vec3f d = normalize(ray.d);
  // Inside or outside from the geometric normal and the ray, never the shading normal.
  const bool entering = dot(d, sp.ng) < 0;
  const Vec3f n = entering ? sp.ng : -sp.ng;
  const float etaI = entering ? 1.0f : m.ior, etaT = entering ? m.ior : 1.0f;
  const float cosI = -dot(d, n);
  const float R = m.fresnel == FresnelModel::Exact ? fresnelDielectric(cosI, etaI, etaT)
                                                   : fresnelSchlick(cosI, etaI, etaT);
  // The reflected ray stays on the side it came from; the refracted one crosses.
  const DielectricMaterial* sameSide = entering ? nullptr : &m;
  const DielectricMaterial* otherSide = entering ? &m : nullptr;
  Rgb L;
  const Rgb reflWeight = throughput * R;
  if (reflWeight.maxChannel() >= kMinThroughput) {
    ++counters.reflection;
    L += R * Li(spawnRay(sp, reflect(d, n), ray.time), depth + 1, reflWeight, sameSide, counters);
  }
  Vec3f t;
  const Rgb transWeight = throughput * (1 - R);
  if (R < 1 && transWeight.maxChannel() >= kMinThroughput && refract(d, n, etaI / etaT, t)) {
    ++counters.refraction;
    L += (1 - R) * Li(spawnRay(sp, t, ray.time), depth + 1, transWeight, otherSide, counters);
  }
  return L;
}

}  // namespace glint
