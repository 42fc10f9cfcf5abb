#include "integrator/whitted.h"

#include <cmath>

#include "integrator/optics.h"

namespace glint {

namespace {

// Shadow rays give up after this many dielectric interfaces and count the light as blocked.
constexpr int kMaxShadowInterfaces = 64;

// Seed 000 §13.4.4: perturb a unit direction r over a square of width `a` orthogonal to r.
Vec3f perturb(const Vec3f& r, float a, Vec2f u) {
  const Vec3f helper = std::fabs(r.x) > 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0};
  const Vec3f e1 = normalize(cross(r, helper));
  const Vec3f e2 = cross(r, e1);
  return normalize(r + (a * (u.x - 0.5f)) * e1 + (a * (u.y - 0.5f)) * e2);
}

float fresnel(const DielectricMaterial& m, float cosI, float etaI, float etaT) {
  return m.fresnel == FresnelModel::Exact ? fresnelDielectric(cosI, etaI, etaT)
                                          : fresnelSchlick(cosI, etaI, etaT);
}

}  // namespace

template <unsigned C>
const DielectricMaterial* WhittedKernel<C>::dielectric(uint32_t materialId) const {
  return std::get_if<DielectricMaterial>(&scene_.materials[materialId].material);
}

template <unsigned C>
float WhittedKernel<C>::iorOutside(const MediumStack& media) const {
  return media.empty() ? 1.0f : dielectric(media.innermostMaterial())->ior;
}

template <unsigned C>
Radiance WhittedKernel<C>::trace(const Ray& cameraRay, const SampleKey& key, RayCounters& counters,
                                 AovSample* aov) const {
  return trace(cameraRay, accel_.intersect(cameraRay), key, counters, aov);
}

template <unsigned C>
Radiance WhittedKernel<C>::trace(const Ray& cameraRay, const Hit& cameraHit, const SampleKey& key,
                                 RayCounters& counters, AovSample* aov) const {
  ++counters.camera;
  bool hit = false;
  Radiance r;
  Branch root;
  root.key = &key;
  r.L = shade(cameraRay, cameraHit, root, counters, &hit, aov);
  r.alpha = hit ? 1.0f : 0.0f;
  return r;
}

template <unsigned C>
void WhittedKernel<C>::recordAov(const Ray& ray, const Hit& hit, const ShadingPoint& sp,
                                 const Material& material, AovSample& aov) const {
  aov.hit = true;
  aov.depth = dot(sp.p - ray.o, aov.viewAxis);
  aov.normal = faceForward(sp.ns, -ray.d);
  aov.position = toFloat(toDouble(sp.p) + scene_.worldOrigin);  // world, not render space
  // The top-level object: for a hit inside an instance, the instance's entry in `objects`.
  const Geometry& top =
      scene_.groups[0].geometries[hit.instId != kInvalidId ? hit.instId : hit.geomId];
  aov.objectId = top.objectId + 1;
  if (const auto* phong = std::get_if<PhongMaterial>(&material))
    aov.albedo = phong->kd.eval(sp.p, scene_.worldOrigin);
  else if (const auto* mirror = std::get_if<MirrorMaterial>(&material))
    aov.albedo = mirror->km;
  else
    aov.albedo = {1, 1, 1};
}

template <unsigned C>
Rgb WhittedKernel<C>::shade(const Ray& ray, const Hit& hit, const Branch& branch,
                            RayCounters& counters, bool* hitSomething, AovSample* aov) const {
  // Beer's law over the segment just travelled, in the medium the ray was inside.
  Rgb absorbed{1, 1, 1};
  if constexpr (kMedia)
    if (!branch.media.empty())
      absorbed =
          beer(dielectric(branch.media.innermostMaterial())->attenuation, hit.t * length(ray.d));
  if (!hit) return scene_.render.background * absorbed;
  if (hitSomething) *hitSomething = true;

  const ShadingPoint sp = scene_.shadingPoint(ray, hit);
  const Material& material = scene_.materials[sp.materialId].material;
  if constexpr (!kAovs) aov = nullptr;
  if (aov) recordAov(ray, hit, sp, material, *aov);
  Rgb L;
  if (const auto* phong = std::get_if<PhongMaterial>(&material)) {
    L = shadePhong(*phong, sp, normalize(-ray.d), ray.time, branch, counters,
                   aov ? aov->perLight : nullptr);
    if (aov) aov->direct = L;
    L += reflectRay(phong->km, phong->gloss, sp, ray, branch, counters);
  } else if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
    L = reflectRay(mirror->km, mirror->gloss, sp, ray, branch, counters);
  } else if constexpr (kMedia) {
    L = shadeDielectric(hit, std::get<DielectricMaterial>(material), sp, ray, branch, counters);
  }
  return L * absorbed;
}

template <unsigned C>
Rgb WhittedKernel<C>::shadePhong(const PhongMaterial& m, const ShadingPoint& sp, const Vec3f& wo,
                                 float time, const Branch& branch, RayCounters& counters,
                                 Rgb* perLight) const {
  // Seed 000 eq. 4.4 / seed 001 §5: surfaces are two-sided, so the normal faces the viewer.
  const Vec3f n = faceForward(sp.ns, wo);
  const Rgb kd = m.kd.eval(sp.p, scene_.worldOrigin);
  Rgb L = m.ka.eval(sp.p, scene_.worldOrigin) * scene_.render.ambient;
  for (size_t li = 0; li < scene_.lights.size(); ++li) {
    const Light& light = scene_.lights[li];
    // Delta lights take one shadow ray and draw no sample; area lights average `samples`
    // points from their own stratified, shuffled set (seed 000 §13.4.2).
    // Without area lights every light is a delta light: one ray, no sample drawn.
    const int count = kAreaLights ? lightSampleCount(light) : 1;
    const bool delta = !kAreaLights || std::holds_alternative<PointLight>(light) ||
                       std::holds_alternative<DirectionalLight>(light);
    const SamplePattern pattern =
        delta ? SamplePattern{}
              : branch.key->pattern(dimension(Dim::Light, branch.depth, static_cast<int>(li)));
    Rgb sum;
    // Sample points are drawn a batch ahead of their shadow rays: drawing one is a long chain
    // of dependent integer operations (sampler.cpp), and a batch's chains run side by side,
    // where alternating with traversal would wait out each chain in turn.
    constexpr int kBatch = 8;
    Vec2f batch[kBatch];
    for (int first = 0; first < count; first += kBatch) {
      const int size = std::min(kBatch, count - first);
      for (int j = 0; j < size; ++j)
        batch[j] = delta ? Vec2f{0.5f, 0.5f} : branch.key->get2D(pattern, first + j, count);
      for (int j = 0; j < size; ++j) {
        const LightSample ls = sampleLight(light, sp.p, batch[j]);
        const float cosL = dot(n, ls.wi);
        if (cosL <= 0 || ls.intensity.isBlack()) continue;
        const Rgb visible = shadowTransmission(sp, ls, time, counters);
        if (visible.isBlack()) continue;
        Rgb f = kd * cosL;
        if (!m.ks.isBlack()) {
          const float spec = m.specularModel == SpecularModel::BlinnPhong
                                 ? dot(n, normalize(ls.wi + wo))
                                 : dot(reflect(-ls.wi, n), wo);
          f += m.ks * specularPower(std::max(0.0f, spec), m.exponent);
        }
        sum += f * ls.intensity * visible;
      }
    }
    const Rgb contribution = count == 1 ? sum : sum * (1.0f / static_cast<float>(count));
    L += contribution;
    if (perLight && li < size_t(AovSet::kMaxLights)) perLight[li] = contribution;
  }
  return L;
}

template <unsigned C>
Rgb WhittedKernel<C>::shadowTransmission(const ShadingPoint& sp, const LightSample& ls, float time,
                                         RayCounters& counters) const {
  ++counters.shadow;
  Ray shadow = ls.atInfinity ? spawnRay(sp, ls.wi, time) : spawnRayTo(sp, ls.target, time);
  // Shadows are see-through only where there are dielectrics to see through.
  if (!kMedia || !scene_.render.transparentShadows)
    return accel_.occluded(shadow) ? Rgb{} : Rgb{1, 1, 1};

  // Seed 002 §9.1: the shadow ray carries the product of the transmissions of the dielectrics
  // it passes (Fresnel at each interface, Beer inside); refraction of the shadow ray itself is
  // ignored, so it runs straight on. Any opaque surface blocks it.
  Rgb T{1, 1, 1};
  MediumStack media;
  for (int i = 0; i < kMaxShadowInterfaces; ++i) {
    const Hit hit = accel_.intersect(shadow);
    const float travelled = (hit ? hit.t : shadow.tMax) * length(shadow.d);
    if (!media.empty()) T *= beer(dielectric(media.innermostMaterial())->attenuation, travelled);
    if (!hit) return T;
    const ShadingPoint next = scene_.shadingPoint(shadow, hit);
    const DielectricMaterial* d = dielectric(next.materialId);
    if (!d) return {};
    const Vec3f dir = normalize(shadow.d);
    const uint64_t key = objectKey(hit);
    const bool entering = dot(dir, next.ng) < 0;
    const float etaI = entering ? iorOutside(media) : d->ior;
    const MediumStack after = entering ? media.entered(key, next.materialId) : media.left(key);
    const float etaT = entering ? d->ior : iorOutside(after);
    T *= 1 - fresnel(*d, std::fabs(dot(dir, next.ng)), etaI, etaT);
    if (T.maxChannel() < minThroughput_) return {};
    media = after;
    // Continue over the rest of the segment from just past this interface.
    const Vec3f target = shadow.at(shadow.tMax);
    ++counters.shadow;
    shadow = ls.atInfinity ? spawnRay(next, dir, time) : spawnRayTo(next, target, time);
  }
  return {};
}

template <unsigned C>
Rgb WhittedKernel<C>::reflectRay(const Rgb& km, float gloss, const ShadingPoint& sp, const Ray& ray,
                                 const Branch& branch, RayCounters& counters) const {
  // Seed 000 §4.8: no ray when k_m is black, past the depth limit, or when the branch's
  // throughput is negligible.
  const Branch next = branch.next(km, branch.media);
  if (km.isBlack() || next.depth > scene_.render.maxDepth ||
      next.throughput.maxChannel() < minThroughput_)
    return {};
  const Vec3f d = normalize(ray.d);
  const Vec3f n = faceForward(sp.ns, -d);
  Vec3f r = reflect(d, n);
  if (kGloss && gloss > 0) {
    // Glossy reflection (seed 000 §13.4.4): a perturbed ray below the surface returns black.
    r = perturb(r, gloss, branch.key->get2D(dimension(Dim::Gloss, branch.depth)));
    if (dot(r, n) <= 0) return {};
  }
  ++counters.reflection;
  return km * Li(spawnRay(sp, r, ray.time), next, counters);
}

template <unsigned C>
Rgb WhittedKernel<C>::shadeDielectric(const Hit& hit, const DielectricMaterial& m,
                                      const ShadingPoint& sp, const Ray& ray, const Branch& branch,
                                      RayCounters& counters) const {
  if constexpr (!kMedia) {
    return {};  // never called: without the capability there are no dielectrics
  } else {
    if (branch.depth + 1 > scene_.render.maxDepth) return {};
    const Vec3f d = normalize(ray.d);
    // Entering or leaving from the geometric normal and the ray, never the shading normal; the
    // interior list says which medium lies on the other side.
    const uint64_t key = objectKey(hit);
    const bool entering = dot(d, sp.ng) < 0;
    const Vec3f n = dot(d, sp.ng) < 0 ? sp.ng : -sp.ng;
    const MediumStack across =
        entering ? branch.media.entered(key, sp.materialId) : branch.media.left(key);
    const float etaI = entering ? iorOutside(branch.media) : m.ior;
    const float etaT = entering ? m.ior : iorOutside(across);
    const float cosI = -dot(d, n);
    const float R = fresnel(m, cosI, etaI, etaT);

    Rgb L;
    const Branch reflected = branch.next(Rgb{R, R, R}, branch.media);
    if (reflected.throughput.maxChannel() >= minThroughput_) {
      ++counters.reflection;
      L += R * Li(spawnRay(sp, reflect(d, n), ray.time), reflected, counters);
    }
    Vec3f t;
    const Branch refracted = branch.next(Rgb{1 - R, 1 - R, 1 - R}, across);
    if (R < 1 && refracted.throughput.maxChannel() >= minThroughput_ &&
        refract(d, n, etaI / etaT, t)) {
      if (kGloss && m.blur > 0) {
        // Blurred translucency (seed 002 §9.3): the same square perturbation around t; a ray
        // that ends up on the incoming side returns black.
        t = perturb(t, m.blur, branch.key->get2D(dimension(Dim::Gloss, branch.depth, 1)));
        if (dot(t, n) >= 0) return L;
      }
      ++counters.refraction;
      L += (1 - R) * Li(spawnRay(sp, t, ray.time), refracted, counters);
    }
    return L;
  }
}

// Every capability set, so render_job.cpp can pick any of them (kernel_caps.h).
static_assert(cap::kAll == 31, "instantiate every capability set below");
#define GLINT_KERNELS_4(base)               \
  template class WhittedKernel<(base)>;     \
  template class WhittedKernel<(base) + 1>; \
  template class WhittedKernel<(base) + 2>; \
  template class WhittedKernel<(base) + 3>;
GLINT_KERNELS_4(0)
GLINT_KERNELS_4(4)
GLINT_KERNELS_4(8)
GLINT_KERNELS_4(12)
GLINT_KERNELS_4(16)
GLINT_KERNELS_4(20)
GLINT_KERNELS_4(24)
GLINT_KERNELS_4(28)
#undef GLINT_KERNELS_4

}  // namespace glint
