#include "integrator/transparent_shadow.h"

#include <cmath>

namespace glint {

Rgb transparentShadow(const Scene& scene, const Accelerator& accel, Ray shadow, bool atInfinity,
                      MediumStack media, float minThroughput, RayCounters& counters) {
  ++counters.shadow;
  Rgb T{1, 1, 1};
  for (int i = 0; i < kMaxShadowInterfaces; ++i) {
    const Hit hit = accel.intersect(shadow);
    // Beer's law over the segment, inside the innermost medium.
    const float travelled = (hit ? hit.t : shadow.tMax) * length(shadow.d);
    if (!media.empty())
      T *=
          scene.materials[media.innermostMaterial()].dielectric.absorption.transmittance(travelled);
    if (!hit) return T;
    const ShadingPoint next = scene.shadingPoint(shadow, hit);
    const Material& m = scene.materials[next.materialId];
    if (!m.refracts()) return {};
    const Vec3f dir = normalize(shadow.d);
    // The interface's transmittance for the straight ray, with the media on both sides.
    const Crossing c = crossingAt(media, hit, next.materialId, dir, next.ng, scene.materials);
    T *= m.dielectric.transmittance(std::fabs(dot(dir, next.ng)), c.etaI, c.etaT);
    if (T.maxChannel() < minThroughput) return {};
    media = c.across;
    // On over the rest of the segment from just past this interface.
    const Vec3f target = shadow.at(shadow.tMax);
    ++counters.shadow;
    shadow = atInfinity ? spawnRay(next, dir, shadow.time) : spawnRayTo(next, target, shadow.time);
  }
  return {};
}

}  // namespace glint
