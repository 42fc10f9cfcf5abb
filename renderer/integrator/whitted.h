#pragma once
// Recursive ray tracing of seed 002 §9.1 Trace(r, d): local Phong / Blinn-Phong shading with
// ambient light and shadows, ideal mirror reflection, and dielectrics with Fresnel, total
// internal reflection and Beer's law. Materials are dispatched here and nowhere else.
#include "accel/accelerator.h"
#include "core/rgb.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

// A branch whose throughput falls below this (in every channel) is not traced further: it could
// change its pixel by at most this much times the radiance behind it.
inline constexpr float kMinThroughput = 1.0f / 1024.0f;

struct Radiance {
  Rgb L;
  float alpha = 0;  // 1 when the camera ray hit geometry
};

class WhittedIntegrator {
 public:
  WhittedIntegrator(const Scene& scene, const Accelerator& accel) : scene_(scene), accel_(accel) {}

  Radiance trace(const Ray& cameraRay, RayCounters& counters) const;

 private:
  // `medium` is the dielectric the ray travels inside, or nullptr for the outside world.
  Rgb Li(const Ray& ray, int depth, const Rgb& throughput, const DielectricMaterial* medium,
         RayCounters& counters, bool* hitSomething = nullptr) const;
  Rgb shadePhong(const PhongMaterial& m, const ShadingPoint& sp, const Vec3f& wo, float time,
                 RayCounters& counters) const;
  Rgb reflectRay(const Rgb& km, const ShadingPoint& sp, const Ray& ray, int depth,
                 const Rgb& throughput, const DielectricMaterial* medium,
                 RayCounters& counters) const;
  Rgb shadeDielectric(const DielectricMaterial& m, const ShadingPoint& sp, const Ray& ray,
                      int depth, const Rgb& throughput, RayCounters& counters) const;

  const Scene& scene_;
  const Accelerator& accel_;
};

}  // namespace glint
