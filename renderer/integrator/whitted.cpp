#include "integrator/whitted.h"

#include <algorithm>
#include <cmath>

#include "integrator/optics.h"

namespace glint {

namespace {

// Shadow rays give up after this many dielectric interfaces and count the light as blocked.
constexpr int kMaxShadowInterfaces = 64;

// Fewer queued shadow rays than this are traced one by one: a stream's set-up costs more than
// packets save on a handful of rays (docs/performance.md).
constexpr size_t kMinShadowStream = 8;

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
  const auto scratch = std::make_unique<Scratch>();
  Radiance r;
  traceCameraHits(&cameraRay, &cameraHit, &key, 1, &r, &aov, counters, *scratch);
  return r;
}

template <unsigned C>
void WhittedKernel<C>::traceCameraHits(const Ray* rays, const Hit* hits, const SampleKey* keys,
                                       int count, Radiance* out, AovSample* const* aovs,
                                       RayCounters& counters, Scratch& scratch) const {
  counters.camera += static_cast<uint64_t>(count);
  for (int begin = 0; begin < count; begin += kChunk) {
    const int n = std::min(kChunk, count - begin);
    for (int i = 0; i < n; ++i) scratch.roots[i].key = &keys[begin + i];  // the rest never changes
    scratch.lightPointsDrawn = false;
    shadeChunk(rays + begin, hits + begin, scratch.roots, n, scratch.cameraRadiance,
               kAovs && aovs ? aovs + begin : nullptr, keys + begin, counters, scratch);
    for (int i = 0; i < n; ++i) {
      Radiance& r = out[begin + i];
      r.L = scratch.cameraRadiance[i];
      r.alpha = hits[begin + i] ? 1.0f : 0.0f;
      r.valid = true;
    }
  }
}

template <unsigned C>
typename WhittedKernel<C>::Generation& WhittedKernel<C>::generation(Scratch& scratch,
                                                                    int depth) const {
  auto& generations = scratch.generations;
  while (generations.size() <= static_cast<size_t>(depth))
    generations.push_back(std::make_unique<Generation>());
  return *generations[static_cast<size_t>(depth)];
}

template <unsigned C>
void WhittedKernel<C>::shadeChunk(const Ray* rays, const Hit* hits, const Branch* branches, int n,
                                  Rgb* radiance, AovSample* const* aovs,
                                  const SampleKey* cameraKeys, RayCounters& counters,
                                  Scratch& scratch) const {
  Generation& gen = generation(scratch, branches[0].depth);
  gen.children = 0;
  const auto& queue = scratch.queue;
  scratch.pendingCount = 0;
  // Each hit's shading point; a Phong hit left pending for its direct light (the pending
  // points lit whenever the next one's shadow rays might not fit the queue) or, past the
  // queue's size, lit on its own; the rays it spawns.
  for (int i = 0; i < n; ++i) {
    const Ray& ray = rays[i];
    const Hit& hit = hits[i];
    const Branch& branch = branches[i];
    auto& sum = gen.sums[i];
    // Beer's law over the segment just travelled, in the medium the ray was inside.
    sum.inMedium = !branch.media.empty();
    if constexpr (kMedia)
      if (sum.inMedium)
        sum.absorbed =
            media_[branch.media.innermostMaterial()].transmittance(hit.t * length(ray.d));
    Rgb& local = sum.local;
    if (!hit) {
      local = scene_.render.background;
      sum.childEnd = gen.children;
      continue;
    }
    local = {};
    AovSample* aov = kAovs && aovs ? aovs[i] : nullptr;
    const Material& material = scene_.materials[scene_.geometry(hit).materialId].material;
    if (const auto* phong = std::get_if<PhongMaterial>(&material)) {
      const bool alone = shadowRaysPerPoint_ > queue.kCapacity;
      if (!alone && (scratch.pendingCount + 1) * shadowRaysPerPoint_ > queue.kCapacity)
        lightPendingPoints(scratch, gen.sums, aovs, cameraKeys != nullptr, counters);
      // The next pending slot, also for a point traced alone (finished before the next hit).
      auto& p = scratch.pending[scratch.pendingCount];
      scene_.shadingPoint(ray, hit, p.pt.sp);
      initPhongPoint(p.pt, *phong, normalize(-ray.d), ray.time, branch);
      if (aov) recordAov(ray, hit, p.pt.sp, material, *aov);
      if (alone) {
        local = shadePhongAlone(p.pt, counters, aov ? aov->perLight : nullptr);
        if (aov) aov->direct = local;
      } else {
        local = ambient(p.pt);
        if (kAreaLights && cameraKeys && !scratch.lightPointsDrawn) {
          drawLightPoints(cameraKeys, n, scratch);
          scratch.lightPointsDrawn = true;
        }
        p.ray = i;
        ++scratch.pendingCount;
      }
      spawnReflection(phong->km, phong->gloss, p.pt.sp, ray, branch, gen, counters);
    } else {
      const ShadingPoint sp = scene_.shadingPoint(ray, hit);
      if (aov) recordAov(ray, hit, sp, material, *aov);
      if (const auto* mirror = std::get_if<MirrorMaterial>(&material))
        spawnReflection(mirror->km, mirror->gloss, sp, ray, branch, gen, counters);
      else if constexpr (kMedia)
        spawnDielectric(hit, std::get<DielectricMaterial>(material), sp, ray, branch, gen,
                        counters);
    }
    sum.childEnd = gen.children;
  }
  lightPendingPoints(scratch, gen.sums, aovs, cameraKeys != nullptr, counters);
  // The next generation: the spawned rays traced, then shaded a chunk at a time.
  if (gen.children > 0) {
    // The camera hits' reflections and refractions leave neighbouring pixels close together
    // and point alike: a coherent stream. Deeper generations have scattered: in a box of
    // mirrors, 60 to 1000 bounces deep, a stream took 8-17 % longer than one ray at a time; on
    // default and whitted the two measured within 2 % from the second generation on.
    if (cameraKeys)
      accel_.intersectCoherent(gen.rays.data(), gen.hits.data(), static_cast<size_t>(gen.children));
    else
      for (int c = 0; c < gen.children; ++c) gen.hits[c] = accel_.intersect(gen.rays[c]);
    for (int c = 0; c < gen.children; c += kChunk)
      shadeChunk(gen.rays.data() + c, gen.hits.data() + c, gen.branches.data() + c,
                 std::min(kChunk, gen.children - c), gen.radiance.data() + c, nullptr, nullptr,
                 counters, scratch);
  }
  for (int i = 0, c = 0; i < n; ++i) {
    const auto& sum = gen.sums[i];
    Rgb L = sum.local;
    for (; c < sum.childEnd; ++c) L += gen.weight[c] * gen.radiance[c];
    if constexpr (kMedia)
      if (sum.inMedium) L = L * sum.absorbed;
    radiance[i] = L;
  }
}

template <unsigned C>
void WhittedKernel<C>::lightPendingPoints(Scratch& scratch, typename Generation::Sum* sums,
                                          AovSample* const* aovs, bool camera,
                                          RayCounters& counters) const {
  const int pending = scratch.pendingCount;
  if (pending == 0) return;
  auto& queue = scratch.queue;
  const size_t lights = scene_.lights.size();
  // Light by light, every point's samples: the queue comes out sorted by light, and each
  // light's rays, which start close together and converge on it, leave as one coherent run.
  // rayEnd[li · kChunk + k]: one past point k's last ray towards light li.
  std::vector<uint16_t>& rayEnd = scratch.rayEnd;
  if (rayEnd.size() < lights * kChunk) rayEnd.resize(lights * kChunk);
  queue.size = 0;
  for (size_t li = 0; li < lights; ++li) {
    const int samples = sampleCount(scene_.lights[li]);
    const Vec2f* cameraPoints =
        camera && li < kMaxPrecomputedLights ? scratch.lightPointsOf[li] : nullptr;
    for (int k = 0; k < pending; ++k) {
      const auto& p = scratch.pending[k];
      const Vec2f* points = cameraPoints ? cameraPoints + p.ray * samples : nullptr;
      queueLight(p.pt, li, points ? SamplePattern{} : lightPattern(p.pt, li), 0, samples, samples,
                 queue, points);
      rayEnd[li * kChunk + static_cast<size_t>(k)] = static_cast<uint16_t>(queue.size);
    }
  }
  traceShadows(queue, counters);
  for (int k = 0; k < pending; ++k) {
    const auto& p = scratch.pending[k];
    AovSample* aov = kAovs && aovs ? aovs[p.ray] : nullptr;
    Rgb L = sums[p.ray].local;
    for (size_t li = 0; li < lights; ++li) {
      const size_t slot = li * kChunk + static_cast<size_t>(k);
      const int begin = k > 0 ? rayEnd[slot - 1] : li > 0 ? rayEnd[slot - kChunk + pending - 1] : 0;
      addContribution(sumVisible(queue, begin, rayEnd[slot]), li, L, aov ? aov->perLight : nullptr);
    }
    if (aov) aov->direct = L;
    sums[p.ray].local = L;
  }
  queue.size = 0;
  scratch.pendingCount = 0;
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
void WhittedKernel<C>::initPhongPoint(PhongPoint& pt, const PhongMaterial& m, const Vec3f& wo,
                                      float time, const Branch& branch) const {
  pt.material = &m;
  pt.wo = wo;
  // Seed 000 eq. 4.4 / seed 001 §5: surfaces are two-sided, so the normal faces the viewer.
  pt.n = faceForward(pt.sp.ns, wo);
  pt.kd = m.kd.eval(pt.sp.p, scene_.worldOrigin);
  pt.time = time;
  pt.branch = &branch;
}

template <unsigned C>
Rgb WhittedKernel<C>::ambient(const PhongPoint& pt) const {
  const PhongMaterial& m = *pt.material;
  const Rgb ka = m.ambientFollowsDiffuse ? pt.kd : m.ka.eval(pt.sp.p, scene_.worldOrigin);
  return ka * scene_.render.ambient;
}

template <unsigned C>
SamplePattern WhittedKernel<C>::lightPattern(const PhongPoint& pt, size_t li) const {
  // Delta lights take one shadow ray and draw no sample; area lights average `samples` points
  // from their own stratified, shuffled set (seed 000 §13.4.2). Without area lights every
  // light is a delta light.
  if (isDelta(scene_.lights[li])) return {};
  return pt.branch->key->pattern(dimension(Dim::Light, pt.branch->depth, static_cast<int>(li)));
}

template <unsigned C>
void WhittedKernel<C>::drawLightPoints(const SampleKey* keys, int count, Scratch& scratch) const {
  const Vec2f** points = scratch.lightPointsOf;
  std::fill_n(points, kMaxPrecomputedLights, nullptr);
  int used = 0;
  for (size_t li = 0; li < scene_.lights.size() && li < kMaxPrecomputedLights; ++li) {
    const Light& light = scene_.lights[li];
    const int n = sampleCount(light);
    if (isDelta(light) || used + count * n > Scratch::kMaxLightPoints) continue;
    points[li] = scratch.lightPoints + used;
    // Per pixel: its run of samples key.index + i, sub-samples j, is one run of flat indices
    // (key.index + i)·n + j of its set.
    for (int begin = 0, end; begin < count; begin = end) {
      const SampleKey& key = keys[begin];
      for (end = begin + 1; end < count && keys[end].px == key.px && keys[end].py == key.py;) ++end;
      key.get2D(key.pattern(dimension(Dim::Light, 0, static_cast<int>(li))), 0, (end - begin) * n,
                n, scratch.lightPoints + used + begin * n);
    }
    used += count * n;
  }
}

template <unsigned C>
template <class Queue>
void WhittedKernel<C>::queueLight(const PhongPoint& pt, size_t li, const SamplePattern& pattern,
                                  int first, int size, int count, Queue& queue,
                                  const Vec2f* points) const {
  const Light& light = scene_.lights[li];
  const bool delta = isDelta(light);
  const PhongMaterial& m = *pt.material;
  // Sample points are drawn a batch ahead of their shadow rays: drawing one is a long chain of
  // dependent integer operations (sampler.cpp), and a batch's chains run side by side.
  constexpr int kBatch = 8;
  Vec2f batch[kBatch];
  for (int begin = first; begin < first + size; begin += kBatch) {
    const int n = std::min(kBatch, first + size - begin);
    const Vec2f* u = batch;
    if (delta)
      batch[0] = {0.5f, 0.5f};
    else if (points)
      u = points + begin;
    else
      pt.branch->key->get2D(pattern, begin, n, count, batch);
    for (int j = 0; j < n; ++j) {
      const LightSample ls = sampleLight(light, pt.sp.p, u[j]);
      const float cosL = dot(pt.n, ls.wi);
      if (cosL <= 0 || ls.intensity.isBlack()) continue;
      Rgb f = pt.kd * cosL;
      if (!m.ks.isBlack()) {
        const float spec = m.specularModel == SpecularModel::BlinnPhong
                               ? dot(pt.n, normalize(ls.wi + pt.wo))
                               : dot(reflect(-ls.wi, pt.n), pt.wo);
        f += m.ks * specularPower(std::max(0.0f, spec), m.exponent);
      }
      const int q = queue.size++;
      spawnRayInto(queue.rays[q], pt.sp, !ls.atInfinity, ls.atInfinity ? ls.wi : ls.target,
                   pt.time);
      queue.term[q] = f * ls.intensity;
      queue.atInfinity[q] = ls.atInfinity;
    }
  }
}

template <unsigned C>
template <class Queue>
void WhittedKernel<C>::traceShadows(Queue& queue, RayCounters& counters) const {
  const auto n = static_cast<size_t>(queue.size);
  // Shadows are see-through only where there are dielectrics to see through.
  if (transparentShadows()) {
    for (size_t i = 0; i < n; ++i)
      queue.visible[i] = shadowTransmission(queue.rays[i], queue.atInfinity[i], counters);
    return;
  }
  counters.shadow += n;
  if (n < kMinShadowStream) {
    for (size_t i = 0; i < n; ++i) queue.blocked[i] = accel_.occluded(queue.rays[i]);
    return;
  }
  // The queue is sorted by light (lightPendingPoints queues light by light, shadePhongAlone
  // one light at a time): each light's rays, which start close together and converge on it
  // (or run parallel), are one coherent run of the stream.
  accel_.occludedCoherent(queue.rays.data(), queue.blocked, n);
}

template <unsigned C>
Rgb WhittedKernel<C>::shadePhongAlone(PhongPoint& pt, RayCounters& counters, Rgb* perLight) const {
  Rgb L = ambient(pt);
  ShadowQueue<8> queue;
  for (size_t li = 0; li < scene_.lights.size(); ++li) {
    const int count = sampleCount(scene_.lights[li]);
    const SamplePattern pattern = lightPattern(pt, li);
    Rgb sum;
    for (int first = 0; first < count; first += queue.kCapacity) {
      queue.size = 0;
      queueLight(pt, li, pattern, first, std::min(queue.kCapacity, count - first), count, queue);
      traceShadows(queue, counters);
      sum = sumVisible(queue, 0, queue.size, sum);
    }
    addContribution(sum, li, L, perLight);
  }
  return L;
}

template <unsigned C>
Rgb WhittedKernel<C>::shadowTransmission(Ray shadow, bool atInfinity, RayCounters& counters) const {
  ++counters.shadow;
  // Seed 002 §9.1: the shadow ray carries the product of the transmissions of the dielectrics
  // it passes (Fresnel at each interface, Beer inside); refraction of the shadow ray itself is
  // ignored, so it runs straight on. Any opaque surface blocks it.
  Rgb T{1, 1, 1};
  MediumStack media;
  for (int i = 0; i < kMaxShadowInterfaces; ++i) {
    const Hit hit = accel_.intersect(shadow);
    const float travelled = (hit ? hit.t : shadow.tMax) * length(shadow.d);
    if (!media.empty()) T *= media_[media.innermostMaterial()].transmittance(travelled);
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
    shadow = atInfinity ? spawnRay(next, dir, shadow.time) : spawnRayTo(next, target, shadow.time);
  }
  return {};
}

template <unsigned C>
void WhittedKernel<C>::spawnReflection(const Rgb& km, float gloss, const ShadingPoint& sp,
                                       const Ray& ray, const Branch& branch, Generation& gen,
                                       RayCounters& counters) const {
  // Seed 000 §4.8: no ray when k_m is black, past the depth limit, or when the branch's
  // throughput is negligible.
  const Rgb throughput = branch.throughput * km;
  if (km.isBlack() || branch.depth + 1 > scene_.render.maxDepth ||
      throughput.maxChannel() < minThroughput_)
    return;
  const Vec3f d = normalize(ray.d);
  const Vec3f n = faceForward(sp.ns, -d);
  Vec3f r = reflect(d, n);
  if (kGloss && gloss > 0) {
    // Glossy reflection (seed 000 §13.4.4): a perturbed ray below the surface returns black.
    r = perturb(r, gloss, branch.key->get2D(dimension(Dim::Gloss, branch.depth)));
    if (dot(r, n) <= 0) return;
  }
  ++counters.reflection;
  spawnRayInto(gen.add(branch, km, throughput, branch.media), sp, false, r, ray.time);
}

template <unsigned C>
void WhittedKernel<C>::spawnDielectric(const Hit& hit, const DielectricMaterial& m,
                                       const ShadingPoint& sp, const Ray& ray, const Branch& branch,
                                       Generation& gen, RayCounters& counters) const {
  if constexpr (kMedia) {  // without the capability there are no dielectrics
    if (branch.depth + 1 > scene_.render.maxDepth) return;
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

    const Rgb reflected = branch.throughput * Rgb{R, R, R};
    if (reflected.maxChannel() >= minThroughput_) {
      ++counters.reflection;
      spawnRayInto(gen.add(branch, Rgb{R, R, R}, reflected, branch.media), sp, false, reflect(d, n),
                   ray.time);
    }
    Vec3f t;
    const Rgb refracted = branch.throughput * Rgb{1 - R, 1 - R, 1 - R};
    if (R < 1 && refracted.maxChannel() >= minThroughput_ && refract(d, n, etaI / etaT, t)) {
      if (kGloss && m.blur > 0) {
        // Blurred translucency (seed 002 §9.3): the same square perturbation around t; a ray
        // that ends up on the incoming side returns black.
        t = perturb(t, m.blur, branch.key->get2D(dimension(Dim::Gloss, branch.depth, 1)));
        if (dot(t, n) >= 0) return;
      }
      ++counters.refraction;
      spawnRayInto(gen.add(branch, Rgb{1 - R, 1 - R, 1 - R}, refracted, across), sp, false, t,
                   ray.time);
    }
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
