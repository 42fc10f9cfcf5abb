#include "integrator/reference.h"

#include "integrator/transparent_shadow.h"

namespace glint {

Radiance ReferenceIntegrator::radiance(const Ray& cameraRay, const SampleKey& key,
                                       RayCounters& counters) const {
  const uint64_t before = counters.total();
  ++counters.camera;
  Branch root;
  root.key = &key;
  const Hit hit = accel_.intersect(cameraRay);
  Radiance out;
  out.L = trace(cameraRay, hit, root, counters);
  out.alpha = hit ? 1.0f : 0.0f;
  out.rays = counters.total() - before;
  return out;
}

Rgb ReferenceIntegrator::trace(const Ray& r, const Hit& q, const Branch& branch,
                               RayCounters& counters) const {
  const RenderSettings& settings = scene_.render;
  if (branch.depth > settings.maxDepth) return scene_.background(r.d);
  Rgb c;
  if (!q) {
    c = scene_.background(r.d);
  } else {
    const ShadingPoint sp = scene_.shadingPoint(r, q);
    const Material& m = scene_.materials[sp.materialId];
    const Vec3f d = normalize(r.d);
    // How far the pixel's cone has come, for image textures only.
    const float distance =
        scene_.features.surfaceCoordinates ? branch.distance + q.t * length(r.d) : 0;
    const SurfacePoint at = lookUp(m.surface, sp, -d, cone_.widthAt(distance), scene_.worldOrigin);
    c = accLightSource(m, sp, at, r.time, branch, counters);
    // The reflected and refracted rays, each traced as Trace(r', d + 1).
    const Crossing crossing =
        m.refracts() ? crossingAt(branch.media, q, sp.materialId, d, sp.ng, scene_.materials)
                     : Crossing{};
    const float gain = coherentGain(m, at);
    forEachCoherentRay(m, sp, at, d, crossing.etaI, crossing.etaT,
                       lobeSamples(m, *branch.key, branch.depth),
                       [&](const Vec3f& direction, const Rgb& weight, bool crosses) {
                         Branch child;
                         child.depth = branch.depth + 1;
                         child.share = branchShare(branch.share, weight, gain);
                         if (child.share.maxChannel() < minThroughput_) return;  // too faint
                         child.media = crosses ? crossing.across : branch.media;
                         child.key = branch.key;
                         child.distance = distance;
                         const Ray childRay = spawnRay(sp, direction, r.time);
                         Hit childHit;  // past the depth limit it is not looked for
                         if (child.depth <= settings.maxDepth) {
                           ++(crosses ? counters.refraction : counters.reflection);
                           childHit = accel_.intersect(childRay);
                         }
                         c += weight * trace(childRay, childHit, child, counters);
                       });
  }
  // Beer's law over the segment r travelled, when it was inside a dielectric.
  if (!branch.media.empty()) {
    const Dielectric& inside = scene_.materials[branch.media.innermostMaterial()].dielectric;
    c = c * inside.absorption.transmittance(q.t * length(r.d));
  }
  return c;
}

Rgb ReferenceIntegrator::accLightSource(const Material& m, const ShadingPoint& q,
                                        const SurfacePoint& at, float time, const Branch& branch,
                                        RayCounters& counters) const {
  Rgb c = ambientAndEmission(m.surface, at, q, scene_.render.ambient, scene_.worldOrigin);
  if (!m.surface.reflectsLights()) return c;
  for (size_t li = 0; li < scene_.lights.size(); ++li) {
    // A delta light is one shadow ray; an area light the mean over `samples` points drawn from
    // its own stratified set (seed 000 §13.4.2).
    const Light& light = scene_.lights[li];
    const int samples = lightSampleCount(light);
    const bool delta = isDeltaLight(light);
    const SamplePattern pattern =
        delta ? SamplePattern{}
              : branch.key->pattern(dimension(Dim::Light, branch.depth, static_cast<int>(li)));
    Rgb sum;
    for (int j = 0; j < samples; ++j) {
      const Vec2f u = delta ? Vec2f{0.5f, 0.5f} : branch.key->get2D(pattern, j, samples);
      const LightSample ls = sampleLight(light, q.p, at.n, u);
      if (!facesLight(at, ls.wi) || ls.intensity.isBlack()) continue;
      const Rgb f = reflectedLight(m.surface, q, at, ls.wi);  // diffuse and highlight
      const Ray shadow =
          spawnShadowRay(q, !ls.atInfinity, ls.atInfinity ? ls.wi : ls.target, time, li);
      const Rgb term = f * ls.intensity;
      if (scene_.render.transparentShadows) {
        const Rgb visible = visibility(shadow, ls.atInfinity, branch, counters);
        if (!visible.isBlack()) sum += term * visible;
      } else if (!visibility(shadow, ls.atInfinity, branch, counters).isBlack()) {
        sum += term;
      }
    }
    c += meanOverSamples(sum, samples);
  }
  return c;
}

Rgb ReferenceIntegrator::visibility(const Ray& shadow, bool atInfinity, const Branch& branch,
                                    RayCounters& counters) const {
  if (scene_.render.transparentShadows)
    return transparentShadow(scene_, accel_, shadow, atInfinity, branch.media, minThroughput_,
                             counters);
  ++counters.shadow;
  return accel_.occluded(shadow) ? Rgb{} : Rgb{1, 1, 1};
}

}  // namespace glint
