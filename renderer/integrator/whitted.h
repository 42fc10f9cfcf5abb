#pragma once
// Recursive ray tracing of seed 002 §9.1 Trace(r, d): local Phong / Blinn-Phong shading with
// ambient light and shadows (optionally transparent), ideal mirror reflection, and dielectrics
// with Fresnel, total internal reflection, Beer's law and nesting. Materials are dispatched
// here and nowhere else.
#include <type_traits>

#include "accel/accelerator.h"
#include "core/rgb.h"
#include "core/sampler.h"
#include "integrator/aov.h"
#include "integrator/kernel_caps.h"
#include "integrator/medium_stack.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

// A branch whose throughput falls below this in every channel is not traced: it could change
// its pixel by at most this much times the radiance behind it (docs/shading.md).
inline constexpr float kDefaultMinThroughput = 1.0f / 1024.0f;

// Which camera sample is being traced: keys every random number drawn along its paths.
struct SampleKey {
  SampleKey(const Sampler* s, int x, int y, int i)
      : SampleKey(s, x, y, i, s ? s->pixelKey(x, y) : 0) {}
  // With the pixel's key computed once for all its samples (Sampler::pixelKey).
  SampleKey(const Sampler* s, int x, int y, int i, uint64_t key)
      : sampler(s), px(x), py(y), index(i), pixelKey(key) {}

  const Sampler* sampler = nullptr;
  int px = 0, py = 0, index = 0;
  uint64_t pixelKey = 0;

  // A dimension's pattern, for drawing several sub-samples of it (a light's shadow samples).
  SamplePattern pattern(uint32_t dim) const { return sampler->pattern(pixelKey, dim); }
  Vec2f get2D(const SamplePattern& pattern, int sub, int count) const {
    return sampler->get2DFor(pattern, index, sub, count);
  }
  Vec2f get2D(uint32_t dim, int sub = 0, int count = 1) const {
    return get2D(pattern(dim), sub, count);
  }
};

struct Radiance {
  Rgb L;
  float alpha = 0;    // 1 when the camera ray hit geometry
  bool valid = true;  // false for a non-finite sample, which the film counts as black
};

// Compiled once per capability set (integrator/kernel_caps.h): code for a capability the set
// lacks is left out, not skipped at run time. Any instantiation renders the scenes whose
// kernelCaps() it covers; WhittedIntegrator, the general path, renders every scene.
template <unsigned Caps>
class WhittedKernel {
 public:
  WhittedKernel(const Scene& scene, const Accelerator& accel,
                float minThroughput = kDefaultMinThroughput)
      : scene_(scene), accel_(accel), minThroughput_(minThroughput) {}

  // With `aov` (only where Caps has cap::kAovs), also records what the camera ray hit (its
  // viewAxis must be set: the camera's unit view direction, for depth).
  Radiance trace(const Ray& cameraRay, const SampleKey& key, RayCounters& counters,
                 AovSample* aov = nullptr) const;
  // The same for a camera ray whose closest hit is already known (traced with others as a
  // coherent stream, Accelerator::intersectCoherent).
  Radiance trace(const Ray& cameraRay, const Hit& cameraHit, const SampleKey& key,
                 RayCounters& counters, AovSample* aov = nullptr) const;

 private:
  static constexpr bool kMedia = (Caps & cap::kDielectrics) != 0;
  static constexpr bool kAreaLights = (Caps & cap::kAreaLights) != 0;
  static constexpr bool kGloss = (Caps & cap::kGloss) != 0;
  static constexpr bool kAovs = (Caps & cap::kAovs) != 0;

  // Without dielectrics a ray is always in the outside world: no interior list to carry.
  struct NoMedia {
    bool empty() const { return true; }
  };
  using Media = std::conditional_t<kMedia, MediumStack, NoMedia>;

  struct Branch {  // what travels with a ray down the recursion
    int depth = 0;
    Rgb throughput{1, 1, 1};
    [[no_unique_address]] Media media;
    const SampleKey* key = nullptr;

    Branch next(const Rgb& weight, const Media& m) const {
      return {depth + 1, throughput * weight, m, key};
    }
  };

  Rgb Li(const Ray& ray, const Branch& branch, RayCounters& counters) const {
    return shade(ray, accel_.intersect(ray), branch, counters);
  }
  // Radiance along `ray` given its closest hit.
  Rgb shade(const Ray& ray, const Hit& hit, const Branch& branch, RayCounters& counters,
            bool* hitSomething = nullptr, AovSample* aov = nullptr) const;
  // `perLight`, when given, receives each light's contribution (AOVs of the camera hit).
  Rgb shadePhong(const PhongMaterial& m, const ShadingPoint& sp, const Vec3f& wo, float time,
                 const Branch& branch, RayCounters& counters, Rgb* perLight = nullptr) const;
  void recordAov(const Ray& ray, const Hit& hit, const ShadingPoint& sp, const Material& material,
                 AovSample& aov) const;
  // Fraction of a light's intensity that reaches sp along the shadow ray: 0 or 1, or with
  // transparent shadows the product of the dielectric transmissions met on the way.
  Rgb shadowTransmission(const ShadingPoint& sp, const LightSample& ls, float time,
                         RayCounters& counters) const;
  Rgb reflectRay(const Rgb& km, float gloss, const ShadingPoint& sp, const Ray& ray,
                 const Branch& branch, RayCounters& counters) const;
  Rgb shadeDielectric(const Hit& hit, const DielectricMaterial& m, const ShadingPoint& sp,
                      const Ray& ray, const Branch& branch, RayCounters& counters) const;
  float iorOutside(const MediumStack& media) const;
  const DielectricMaterial* dielectric(uint32_t materialId) const;

  const Scene& scene_;
  const Accelerator& accel_;
  float minThroughput_;
};

using WhittedIntegrator = WhittedKernel<cap::kAll>;

}  // namespace glint
