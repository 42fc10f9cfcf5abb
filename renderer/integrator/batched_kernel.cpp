#include "integrator/batched_kernel.h"

#include <algorithm>
#include <cmath>

#include "integrator/transparent_shadow.h"

namespace glint {

namespace {

// Fewer queued shadow rays than this are traced one by one: a stream's set-up costs more than
// packets save on a handful of rays (docs/performance.md).
constexpr size_t kMinShadowStream = 8;

}  // namespace

BatchedKernel::BatchedKernel(const Scene& scene, const Accelerator& accel, float minThroughput,
                             int footprintSpp)
    : scene_(scene),
      accel_(accel),
      minThroughput_(minThroughput),
      cone_(pixelCone(scene.cameraDesc, scene.render.height, footprintSpp)) {
  for (const Light& light : scene.lights) {
    const bool delta = isDeltaLight(light);
    lights_.push_back({lightSampleCount(light), delta});
    shadowRaysPerPoint_ += lights_.back().samples;
    areaLights_ |= !delta;
  }
}

Radiance BatchedKernel::trace(const Ray& cameraRay, const SampleKey& key, RayCounters& counters,
                              AovSample* aov) const {
  const auto scratch = std::make_unique<Scratch>();
  const Hit hit = accel_.intersect(cameraRay);
  Radiance r;
  traceCameraHits(&cameraRay, &hit, &key, 1, &r, &aov, counters, *scratch);
  return r;
}

void BatchedKernel::traceCameraHits(const Ray* rays, const Hit* hits, const SampleKey* keys,
                                    int count, Radiance* out, AovSample* const* aovs,
                                    RayCounters& counters, Scratch& scratch) const {
  counters.camera += static_cast<uint64_t>(count);
  for (int begin = 0; begin < count; begin += kChunk) {
    const int n = std::min(kChunk, count - begin);
    for (int i = 0; i < n; ++i) scratch.roots[i].key = &keys[begin + i];  // the rest never changes
    scratch.lightPointsDrawn = false;
    scratch.rootKeys = keys + begin;
    scratch.rootCount = n;
    std::fill_n(scratch.raysOf, n, uint64_t{0});
    shadeChunk(rays + begin, hits + begin, scratch.roots, n, scratch.cameraRadiance,
               aovs ? aovs + begin : nullptr, keys + begin, counters, scratch);
    for (int i = 0; i < n; ++i) {
      Radiance& r = out[begin + i];
      r.L = scratch.cameraRadiance[i];
      r.alpha = hits[begin + i] ? 1.0f : 0.0f;
      r.valid = true;
      r.rays = 1 + scratch.raysOf[i];
    }
  }
}

BatchedKernel::Generation& BatchedKernel::generation(Scratch& scratch, int depth) const {
  auto& generations = scratch.generations;
  while (generations.size() <= static_cast<size_t>(depth))
    generations.push_back(std::make_unique<Generation>());
  return *generations[static_cast<size_t>(depth)];
}

void BatchedKernel::shadeChunk(const Ray* rays, const Hit* hits, const Branch* branches, int n,
                               Rgb* radiance, AovSample* const* aovs, const SampleKey* cameraKeys,
                               RayCounters& counters, Scratch& scratch) const {
  const int depth = branches[0].depth;  // every ray of a chunk has the same
  Generation& gen = generation(scratch, depth);
  gen.children = 0;
  const auto& queue = scratch.queue;
  scratch.pendingCount = 0;
  const bool pastDepthLimit = depth > scene_.render.maxDepth;
  for (int i = 0; i < n; ++i) {
    auto& sum = gen.sums[i];
    Rgb& local = sum.local;
    // Trace(r, d) returns the background past the depth limit, before it looks for a hit.
    if (pastDepthLimit) {
      local = scene_.background(rays[i].d);
      sum.inMedium = false;
      sum.childEnd = gen.children;
      continue;
    }
    const Ray& ray = rays[i];
    const Hit& hit = hits[i];
    const Branch& branch = branches[i];
    // Beer's law over the segment just travelled, in the medium the ray was inside.
    sum.inMedium = !branch.media.empty();
    if (sum.inMedium)
      sum.absorbed =
          scene_.materials[branch.media.innermostMaterial()].dielectric.absorption.transmittance(
              hit.t * length(ray.d));
    if (!hit) {
      local = scene_.background(ray.d);
      sum.childEnd = gen.children;
      continue;
    }
    const Material& m = scene_.materials[scene_.materialId(hit)];
    AovSample* aov = aovs ? aovs[i] : nullptr;
    const Vec3f wo = normalize(-ray.d);
    const float distance = distanceAt(ray, hit, branch);
    // AccLightSource: what the surface emits and reflects of the ambient light now; the light
    // sources' share, for a surface that reflects them, when the pending points are lit (or at
    // once for a point traced alone).
    if (!m.surface.reflectsLights()) {
      ShadingPoint sp;
      scene_.shadingPoint(ray, hit, sp);
      const SurfacePoint at =
          lookUp(m.surface, sp, wo, cone_.widthAt(distance), scene_.worldOrigin);
      if (aov) recordAov(ray, hit, m, sp, at, *aov);
      local = ambientAndEmission(m.surface, at, sp, scene_.render.ambient, scene_.worldOrigin);
      if (aov) aov->direct = local;
      spawnCoherent(hit, m, sp, at, ray, -wo, branch, distance, gen, counters,
                    scratch.raysOfRoot(branch));
      sum.childEnd = gen.children;
      continue;
    }
    // A lit point waits for its direct light in the pending list; the list is lit first
    // whenever this point's shadow rays might not fit the queue.
    const bool alone = shadowRaysPerPoint_ > queue.kCapacity;
    if (!alone && (scratch.pendingCount + 1) * shadowRaysPerPoint_ > queue.kCapacity)
      lightPendingPoints(scratch, gen.sums, aovs, cameraKeys != nullptr, counters);
    // Shaded in the next pending slot, which it keeps unless it is lit alone.
    auto& p = scratch.pending[scratch.pendingCount];
    LitPoint& pt = p.pt;
    scene_.shadingPoint(ray, hit, pt.sp);
    pt.material = &m;
    pt.at = lookUp(m.surface, pt.sp, wo, cone_.widthAt(distance), scene_.worldOrigin);
    pt.time = ray.time;
    pt.branch = &branch;
    if (aov) recordAov(ray, hit, m, pt.sp, pt.at, *aov);
    local = ambientAndEmission(m.surface, pt.at, pt.sp, scene_.render.ambient, scene_.worldOrigin);
    if (alone) {
      scratch.raysOfRoot(branch) += lightAlone(pt, local, counters, aov ? aov->perLight : nullptr);
      if (aov) aov->direct = local;
    } else {
      if (areaLights_ && cameraKeys && !scratch.lightPointsDrawn) {
        drawLightPoints(cameraKeys, n, scratch);
        scratch.lightPointsDrawn = true;
      }
      p.ray = i;
      ++scratch.pendingCount;
    }
    spawnCoherent(hit, m, pt.sp, pt.at, ray, -wo, branch, distance, gen, counters,
                  scratch.raysOfRoot(branch));
    sum.childEnd = gen.children;
  }
  lightPendingPoints(scratch, gen.sums, aovs, cameraKeys != nullptr, counters);
  // The next generation: the spawned rays traced, then shaded a chunk at a time.
  if (gen.children > 0) {
    if (depth + 1 > scene_.render.maxDepth) {
      // Past the limit: not traced (shadeChunk returns the background for them).
    } else if (cameraKeys) {
      // The camera hits' reflections and refractions leave neighbouring pixels close together
      // and point alike: a coherent stream. Deeper generations have scattered: in a box of
      // mirrors a stream took 8-17 % longer than one ray at a time.
      accel_.intersectCoherent(gen.rays.data(), gen.hits.data(), static_cast<size_t>(gen.children));
    } else {
      for (int c = 0; c < gen.children; ++c) gen.hits[c] = accel_.intersect(gen.rays[c]);
    }
    for (int c = 0; c < gen.children; c += kChunk)
      shadeChunk(gen.rays.data() + c, gen.hits.data() + c, gen.branches.data() + c,
                 std::min(kChunk, gen.children - c), gen.radiance.data() + c, nullptr, nullptr,
                 counters, scratch);
  }
  // Each ray's sum, its children in the order they were spawned.
  for (int i = 0, c = 0; i < n; ++i) {
    const auto& sum = gen.sums[i];
    Rgb L = sum.local;
    for (; c < sum.childEnd; ++c) L += gen.weight[c] * gen.radiance[c];
    if (sum.inMedium) L = L * sum.absorbed;
    radiance[i] = L;
  }
}

void BatchedKernel::spawnCoherent(const Hit& hit, const Material& m, const ShadingPoint& sp,
                                  const SurfacePoint& at, const Ray& ray, const Vec3f& d,
                                  const Branch& branch, float distance, Generation& gen,
                                  RayCounters& counters, uint64_t& sampleRays) const {
  if (!m.refracts() && !m.surface.reflectsCoherently()) return;
  const bool traced = branch.depth + 1 <= scene_.render.maxDepth;
  // Spawns each ray that its throughput keeps; `across`: the interior list beyond the surface.
  const auto spawnInto = [&](const MediumStack& across) {
    return [&](const Vec3f& direction, const Rgb& weight, bool crosses) {
      const Rgb throughput = branch.throughput * weight;
      if (throughput.maxChannel() < minThroughput_) return;
      if (traced) {
        ++(crosses ? counters.refraction : counters.reflection);
        ++sampleRays;
      }
      spawnRayInto(gen.add(branch, weight, throughput, crosses ? across : branch.media, distance),
                   sp, false, direction, ray.time);
    };
  };
  if (m.refracts()) {
    // The indices on both sides, from the interior list.
    const Crossing c = crossingAt(branch.media, hit, sp.materialId, d, sp.ng, scene_.materials);
    forEachCoherentRay(m, sp, at, d, c.etaI, c.etaT, *branch.key, branch.depth,
                       spawnInto(c.across));
    return;
  }
  forEachCoherentRay(m, sp, at, d, 1, 1, *branch.key, branch.depth, spawnInto(branch.media));
}

void BatchedKernel::lightPendingPoints(Scratch& scratch, Generation::Sum* sums,
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
    if (lights_[li].delta) {
      // One shadow ray per point and no sample drawn: the loop says so once per light.
      for (int k = 0; k < pending; ++k) {
        queueSample(scratch.pending[k].pt, li, {0.5f, 0.5f}, queue);
        rayEnd[li * kChunk + static_cast<size_t>(k)] = static_cast<uint16_t>(queue.size);
      }
      continue;
    }
    const int samples = lights_[li].samples;
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
    AovSample* aov = aovs ? aovs[p.ray] : nullptr;
    Rgb L = sums[p.ray].local;
    uint64_t rays = 0;
    for (size_t li = 0; li < lights; ++li) {
      const size_t slot = li * kChunk + static_cast<size_t>(k);
      const int begin = k > 0 ? rayEnd[slot - 1] : li > 0 ? rayEnd[slot - kChunk + pending - 1] : 0;
      addContribution(sumVisible(queue, begin, rayEnd[slot]), li, L, aov ? aov->perLight : nullptr);
      rays += tracedIn(queue, begin, rayEnd[slot]);
    }
    scratch.raysOfRoot(*p.pt.branch) += rays;
    if (aov) aov->direct = L;
    sums[p.ray].local = L;
  }
  queue.size = 0;
  scratch.pendingCount = 0;
}

void BatchedKernel::recordAov(const Ray& ray, const Hit& hit, const Material& m,
                              const ShadingPoint& sp, const SurfacePoint& at,
                              AovSample& aov) const {
  aov.hit = true;
  aov.depth = dot(sp.p - ray.o, aov.viewAxis);
  aov.normal = at.n;  // the normal the surface is lit with: facing the camera, bent by maps
  aov.position = toFloat(toDouble(sp.p) + scene_.worldOrigin);  // world, not render space
  // The object: for a hit inside an instance, the instance's.
  aov.objectId = scene_.objectId(hit) + 1;
  aov.materialId = scene_.materialId(hit);
  aov.albedo = albedo(m, at);
}

SamplePattern BatchedKernel::lightPattern(const LitPoint& pt, size_t li) const {
  // Delta lights take one shadow ray and draw no sample; area lights average `samples` points
  // from their own stratified, shuffled set (seed 000 §13.4.2). Without area lights every
  // light is a delta light.
  if (lights_[li].delta) return {};
  return pt.branch->key->pattern(dimension(Dim::Light, pt.branch->depth, static_cast<int>(li)));
}

void BatchedKernel::drawLightPoints(const SampleKey* keys, int count, Scratch& scratch) const {
  const Vec2f** points = scratch.lightPointsOf;
  std::fill_n(points, kMaxPrecomputedLights, nullptr);
  int used = 0;
  for (size_t li = 0; li < scene_.lights.size() && li < kMaxPrecomputedLights; ++li) {
    const int n = lights_[li].samples;
    if (lights_[li].delta || used + count * n > Scratch::kMaxLightPoints) continue;
    points[li] = scratch.lightPoints + used;
    // Per pixel and half: its run of samples key.index + i, sub-samples j, is one run of flat
    // indices (key.index + i)·n + j of its set.
    for (int begin = 0, end; begin < count; begin = end) {
      const SampleKey& key = keys[begin];
      for (end = begin + 1; end < count && keys[end].px == key.px && keys[end].py == key.py &&
                            keys[end].half == key.half;)
        ++end;
      key.get2D(key.pattern(dimension(Dim::Light, 0, static_cast<int>(li))), 0, (end - begin) * n,
                n, scratch.lightPoints + used + begin * n);
    }
    used += count * n;
  }
}

template <class Queue>
void BatchedKernel::queueLight(const LitPoint& pt, size_t li, const SamplePattern& pattern,
                               int first, int size, int count, Queue& queue,
                               const Vec2f* points) const {
  // Sample points are drawn a batch ahead of their shadow rays: drawing one is a long chain of
  // dependent integer operations (sampler.cpp), and a batch's chains run side by side.
  constexpr int kBatch = 8;
  Vec2f batch[kBatch];
  for (int begin = first; begin < first + size; begin += kBatch) {
    const int n = std::min(kBatch, first + size - begin);
    const Vec2f* u = batch;
    if (points)
      u = points + begin;
    else
      pt.branch->key->get2D(pattern, begin, n, count, batch);
    for (int j = 0; j < n; ++j) queueSample(pt, li, u[j], queue);
  }
}

template <class Queue>
void BatchedKernel::traceShadows(Queue& queue, RayCounters& counters) const {
  const auto n = static_cast<size_t>(queue.size);
  // Shadows are see-through only where there are dielectrics to see through.
  if (transparentShadows()) {
    for (size_t i = 0; i < n; ++i) {
      const uint64_t before = counters.shadow;
      queue.visible[i] = transparentShadow(scene_, accel_, queue.rays[i], queue.atInfinity[i],
                                           *queue.media[i], minThroughput_, counters);
      queue.traced[i] =
          static_cast<uint32_t>(counters.shadow - before);  // at most kMaxShadowInterfaces + 1
    }
    return;
  }
  counters.shadow += n;
  if (n < kMinShadowStream) {
    for (size_t i = 0; i < n; ++i) queue.blocked[i] = accel_.occluded(queue.rays[i]);
    return;
  }
  // The queue is sorted by light (lightPendingPoints queues light by light, lightAlone one
  // light at a time): each light's rays, which start close together and converge on it (or
  // run parallel), are one coherent run of the stream.
  accel_.occludedCoherent(queue.rays.data(), queue.blocked, n);
}

uint64_t BatchedKernel::lightAlone(const LitPoint& pt, Rgb& L, RayCounters& counters,
                                   Rgb* perLight) const {
  ShadowQueue<8> queue;
  uint64_t rays = 0;
  for (size_t li = 0; li < scene_.lights.size(); ++li) {
    const int count = lights_[li].samples;
    const SamplePattern pattern = lightPattern(pt, li);
    Rgb sum;
    for (int first = 0; first < count; first += queue.kCapacity) {
      queue.size = 0;
      if (lights_[li].delta)
        queueSample(pt, li, {0.5f, 0.5f}, queue);
      else
        queueLight(pt, li, pattern, first, std::min(queue.kCapacity, count - first), count, queue);
      traceShadows(queue, counters);
      sum = sumVisible(queue, 0, queue.size, sum);
      rays += tracedIn(queue, 0, queue.size);
    }
    addContribution(sum, li, L, perLight);
  }
  return rays;
}

}  // namespace glint
