#include "accel/origin_rays.h"

#include <cmath>

#include "accel/cross_check.h"
#include "core/hash.h"
#include "core/sampling.h"
#include "scene/scene.h"

namespace glint {

namespace {

Vec3f uniformDirection(float a, float b) {
  const float z = 1 - 2 * a, phi = 2 * kPi * b;
  const float s = std::sqrt(std::max(0.0f, 1 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

void ask(const Accelerator& accel, const Ray& r) {
  if (!rayProblem(r).empty()) return;
  accel.intersect(r);
  accel.occluded(r);
}

}  // namespace

void castOriginRays(const Scene& scene, const Accelerator& finder, const Accelerator& accel,
                    int count, uint64_t seed) {
  const Bounds3f b = randomRayOrigins(scene);
  const std::vector<Geometry>& world = scene.groups[0].geometries;
  const CameraDesc& cam = scene.cameraDesc;
  for (int i = 0; i < count; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(seed, 0x0c0e5e7u, i, k)); };
    const float time = u(0);
    if (cam.projection == Projection::Perspective) {
      Ray r;
      const Vec2f l{2 * u(1) - 1, 2 * u(2) - 1};
      // A point of the square that holds every lens shape, in the lens plane's frame.
      const Vec3f w = normalize(cam.eye - cam.lookAt);
      Vec3f side = cross(cam.up, w);
      side = length(side) > 0 ? normalize(side) : Vec3f{1, 0, 0};
      const Vec3f up = cross(w, side);
      r.o = cam.eye + cam.apertureRadius * (l.x * side + l.y * up);
      r.d = uniformDirection(u(3), u(4));
      r.time = time;
      r.origin = ray_origin::kEye;
      ask(accel, r);
    }
    if (world.empty()) continue;
    const Geometry& g = world[std::min(world.size() - 1, size_t(u(5) * float(world.size())))];
    const Bounds3f box = scene.geometryBounds(g);
    if (box.empty()) continue;
    Ray probe;
    probe.o = b.lo + mul(b.diagonal(), Vec3f{u(6), u(7), u(8)});
    probe.d = box.lo + mul(box.diagonal(), Vec3f{u(9), u(10), u(11)}) - probe.o;
    probe.time = time;
    if (!rayProblem(probe).empty()) continue;
    const Hit h = finder.intersect(probe);
    if (!h) continue;
    const ShadingPoint sp = scene.shadingPoint(probe, h);
    ask(accel, spawnRay(sp, uniformDirection(u(12), u(13)), time));
    if (scene.lights.empty()) continue;
    const size_t k = std::min(scene.lights.size() - 1, size_t(u(14) * float(scene.lights.size())));
    const LightSample ls = sampleLight(scene.lights[k], sp.p, sp.ng, {u(15), u(16)});
    if (!ls.atInfinity) ask(accel, spawnShadowRay(sp, true, ls.target, time, k));
  }
}

}  // namespace glint
