#include "integrator/batched_kernel.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "integrator/point_light_lanes.h"
#include "integrator/transparent_shadow.h"

namespace glint {

namespace {
// What a hit whose material draws no lobe samples spreads by: nothing reads it.
constexpr LobeSamples kNoLobeSamples{};
}  // namespace

BatchedKernel::BatchedKernel(const Scene& scene, const Accelerator& accel, float minThroughput,
                             int footprintSpp)
    : scene_(scene),
      accel_(accel),
      minThroughput_(minThroughput),
      cone_(pixelCone(scene.cameraDesc, scene.render.height, footprintSpp)) {
  for (const Light& light : scene.lights) {
    lights_.push_back({lightSampleCount(light), isDeltaLight(light)});
    shadowRaysPerPoint_ += lights_.back().samples;
  }
  for (const Material& m : scene.materials) {
    materials_.push_back({m.surface.reflectsLights(),
                          m.refracts() || m.surface.reflectsCoherently(), drawsLobeSamples(m)});
    drawsLobes_ |= drawsLobeSamples(m);
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
    scratch.rootKeys = keys + begin;
    scratch.rootCount = n;
    std::fill_n(scratch.raysOf, n, uint64_t{0});
    shadeChunk(rays + begin, hits + begin, scratch.roots, n, scratch.cameraRadiance,
               aovs ? aovs + begin : nullptr, counters, scratch);
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
                               Rgb* radiance, AovSample* const* aovs, RayCounters& counters,
                               Scratch& scratch) const {
  const int depth = branches[0].depth;  // every ray of a chunk has the same
  Generation& gen = generation(scratch, depth);
  shadeHits(rays, hits, branches, n, gen, aovs, counters, scratch);
  lightPendingPoints(scratch, gen.sums, aovs, counters);
  traceGeneration(gen, depth, counters, scratch);
  sumRadiance(gen, n, radiance);
}

void BatchedKernel::shadeHits(const Ray* rays, const Hit* hits, const Branch* branches, int n,
                              Generation& gen, AovSample* const* aovs, RayCounters& counters,
                              Scratch& scratch) const {
  gen.children = 0;
  scratch.pendingCount = 0;
  const bool pastDepthLimit = branches[0].depth > scene_.render.maxDepth;
  // The glossy and blurred hits' lobe samples, drawn side by side (materials' drawLobeSamples).
  UninitializedArray<LobeSamples, kChunk> lobes;
  if (drawsLobes_ && !pastDepthLimit) {
    const Material* lobeMaterials[kChunk];
    const SampleKey* lobeKeys[kChunk];
    int lobeRays[kChunk], count = 0;
    for (int i = 0; i < n; ++i) {
      if (!hits[i]) continue;
      const uint32_t id = scene_.materialId(hits[i]);
      if (!materials_[id].drawsLobes) continue;
      lobeMaterials[count] = &scene_.materials[id];
      lobeKeys[count] = branches[i].key;
      lobeRays[count++] = i;
    }
    drawLobeSamples(lobeMaterials, lobeKeys, lobeRays, branches[0].depth, count, lobes.data());
  }
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
    const uint32_t materialId = scene_.materialId(hit);
    const Material& m = scene_.materials[materialId];
    const MaterialFlags flags = materials_[materialId];
    AovSample* aov = aovs ? aovs[i] : nullptr;
    const Vec3f wo = normalize(-ray.d);
    const float distance = distanceAt(ray, hit, branch);
    // AccLightSource: what the surface emits and reflects of the ambient light now; the light
    // sources' share, for a surface that reflects them, when the pending points are lit.
    if (!flags.reflectsLights) {
      ShadingPoint sp;
      scene_.shadingPoint(ray, hit, sp);
      const SurfacePoint at =
          lookUp(m.surface, sp, wo, cone_.widthAt(distance), scene_.worldOrigin);
      if (aov) recordAov(ray, hit, m, sp, at, *aov);
      local = ambientAndEmission(m.surface, at, sp, scene_.render.ambient, scene_.worldOrigin);
      if (aov) aov->direct = local;
      if (flags.spawnsRays)
        spawnCoherent(hit, m, sp, at, ray, -wo, branch, distance,
                      flags.drawsLobes ? lobes[size_t(i)] : kNoLobeSamples, gen, counters,
                      scratch.raysOfRoot(branch));
      sum.childEnd = gen.children;
      continue;
    }
    // A lit point waits for its direct light in the pending list, which is lit first when this
    // point's shadow rays would not fit the queue beside theirs: each tracing then holds whole
    // points, and a point with more rays than the queue holds is lit on its own.
    if ((scratch.pendingCount + 1) * shadowRaysPerPoint_ > ShadowQueue::kCapacity)
      lightPendingPoints(scratch, gen.sums, aovs, counters);
    auto& p = scratch.pending[scratch.pendingCount++];
    LitPoint& pt = p.pt;
    scene_.shadingPoint(ray, hit, pt.sp);
    pt.material = &m;
    lookUp(m.surface, pt.sp, wo, cone_.widthAt(distance), scene_.worldOrigin, pt.at);
    pt.time = ray.time;
    pt.branch = &branch;
    p.ray = i;
    p.rays = &scratch.raysOfRoot(branch);
    if (aov) recordAov(ray, hit, m, pt.sp, pt.at, *aov);
    local = ambientAndEmission(m.surface, pt.at, pt.sp, scene_.render.ambient, scene_.worldOrigin);
    // Asked here, not in the call: a matte surface's hit paid the call's set-up for nothing.
    if (flags.spawnsRays)
      spawnCoherent(hit, m, pt.sp, pt.at, ray, -wo, branch, distance,
                    flags.drawsLobes ? lobes[size_t(i)] : kNoLobeSamples, gen, counters, *p.rays);
    sum.childEnd = gen.children;
  }
}

void BatchedKernel::traceGeneration(Generation& gen, int depth, RayCounters& counters,
                                    Scratch& scratch) const {
  // Past the limit the rays are not traced: shadeChunk returns the background for them.
  // Every generation leaves as one coherent stream (Embree's packets): a chunk's reflections and
  // refractions start from neighbouring pixels' hits and point alike, and even deep in a closed
  // box of mirrors the stream was faster than one ray at a time.
  if (gen.children > 0 && depth + 1 <= scene_.render.maxDepth)
    accel_.intersectCoherent(gen.rays.data(), gen.hits.data(), static_cast<size_t>(gen.children));
  for (int c = 0; c < gen.children; c += kChunk)
    shadeChunk(gen.rays.data() + c, gen.hits.data() + c, gen.branches.data() + c,
               std::min(kChunk, gen.children - c), gen.radiance.data() + c, nullptr, counters,
               scratch);
}

void BatchedKernel::sumRadiance(const Generation& gen, int n, Rgb* radiance) {
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
                                  const Branch& branch, float distance, const LobeSamples& u,
                                  Generation& gen, RayCounters& counters,
                                  uint64_t& sampleRays) const {
  const bool traced = branch.depth + 1 <= scene_.render.maxDepth;
  // Spawns each ray that its share keeps; `across`: the interior list beyond the surface.
  const float gain = coherentGain(m, at);
  const auto spawnInto = [&](const MediumStack& across) {
    return [&](const Vec3f& direction, const Rgb& weight, bool crosses) {
      const Rgb share = branchShare(branch.share, weight, gain);
      if (share.maxChannel() < minThroughput_) return;
      if (traced) {
        ++(crosses ? counters.refraction : counters.reflection);
        ++sampleRays;
      }
      spawnRayInto(gen.add(branch, weight, share, crosses ? across : branch.media, distance), sp,
                   false, direction, ray.time);
    };
  };
  if (m.refracts()) {
    // The indices on both sides, from the interior list.
    const Crossing c = crossingAt(branch.media, hit, sp.materialId, d, sp.ng, scene_.materials);
    forEachCoherentRay(m, sp, at, d, c.etaI, c.etaT, u, spawnInto(c.across));
    return;
  }
  forEachCoherentRay(m, sp, at, d, 1, 1, u, spawnInto(branch.media));
}

void BatchedKernel::lightPendingPoints(Scratch& scratch, Generation::Sum* sums,
                                       AovSample* const* aovs, RayCounters& counters) const {
  const int pending = scratch.pendingCount;
  if (pending == 0) return;
  // Light by light, every point's samples: the queue comes out sorted by light, and each
  // light's rays, which start close together and converge on it, leave as one coherent run.
  for (size_t li = 0; li < scene_.lights.size(); ++li)
    queueShadowRays(scratch, li, sums, aovs, counters);
  flushShadows(scratch, sums, aovs, counters);
  if (aovs) {
    for (int k = 0; k < pending; ++k) {
      const auto& p = scratch.pending[k];
      if (aovs[p.ray]) aovs[p.ray]->direct = sums[p.ray].local;
    }
  }
  scratch.pendingCount = 0;
}

void BatchedKernel::queueShadowRays(Scratch& scratch, size_t li, Generation::Sum* sums,
                                    AovSample* const* aovs, RayCounters& counters) const {
  std::visit(
      [&](const auto& light) { queueShadowRaysOf(scratch, light, li, sums, aovs, counters); },
      scene_.lights[li]);
}

template <class L>
void BatchedKernel::queueShadowRaysOf(Scratch& scratch, const L& light, size_t li,
                                      Generation::Sum* sums, AovSample* const* aovs,
                                      RayCounters& counters) const {
  auto& queue = scratch.queue;
  const int index = static_cast<int>(li);
  if constexpr (std::is_same_v<L, PointLight> || std::is_same_v<L, DirectionalLight>) {
    // One shadow ray per point and no sample drawn: one run of the light's rays, each naming
    // its point, closed where the queue is traced.
    if (queue.full()) flushShadows(scratch, sums, aovs, counters);
    int begin = queue.size;
    // A point light's samples are set up eight points at a time, in lanes: one at a time, their
    // arithmetic was most of what every lit point cost besides its rays.
    [[maybe_unused]] PointLightLanes lanes;
    [[maybe_unused]] bool inLanes = false;
    if constexpr (std::is_same_v<L, PointLight>) {
      static_assert(kChunk <= PointLightLanes::kMaxPoints);
      inLanes = !light.isSpot();
      if (inLanes)
        samplePointLight(light.position, light.intensity, light.falloff == Falloff::InverseSquare,
                         &scratch.pending[0].pt.sp, &scratch.pending[0].pt.at.n,
                         sizeof(Scratch::Pending), scratch.pendingCount, lanes);
    }
    for (int k = 0; k < scratch.pendingCount; ++k) {
      if (queue.size == ShadowQueue::kCapacity) {
        queue.addRun(ShadowRun::kEachRay, index, false, true);
        flushShadows(scratch, sums, aovs, counters);
        begin = 0;
      }
      queue.pointOf[queue.size] = k;  // read only if the sample is queued
      if constexpr (std::is_same_v<L, PointLight>)
        if (inLanes) {
          queueLaneSample(scratch.pending[k].pt, lanes, k, li, queue);
          continue;
        }
      queueSamples(scratch.pending[k].pt, light, li, nullptr, 1, queue);
    }
    if (queue.size > begin) queue.addRun(ShadowRun::kEachRay, index, false, true);
  } else {
    const int count = lights_[li].samples;
    // Every point's samples of the light drawn a window ahead, several points' side by side.
    SamplePattern patterns[kChunk];
    int indices[kChunk];
    for (int k = 0; k < scratch.pendingCount; ++k) {
      const Branch& b = *scratch.pending[k].pt.branch;
      indices[k] = b.key->index;
      // Consecutive samples of a pixel's half, pending side by side, share its set.
      const Branch* before = k > 0 ? scratch.pending[k - 1].pt.branch : nullptr;
      if (before && before->depth == b.depth && before->key->pixelKey == b.key->pixelKey &&
          before->key->half == b.key->half)
        patterns[k] = patterns[k - 1];
      else
        patterns[k] = lightPattern(scratch.pending[k].pt, li);
    }
    SubSampleStream draws(*scratch.pending[0].pt.branch->key->sampler, count, patterns, indices,
                          scratch.pendingCount);
    for (int k = 0; k < scratch.pendingCount; ++k) {
      for (int first = 0; first < count;) {
        if (queue.full()) flushShadows(scratch, sums, aovs, counters);
        const int size = std::min(count - first, queue.kCapacity - queue.size);
        queueSamples(scratch.pending[k].pt, light, li, &draws, size, queue);
        queue.addRun(k, index, first > 0, first + size == count);
        first += size;
      }
    }
  }
}

void BatchedKernel::queueLaneSample(const LitPoint& pt, const PointLightLanes& lanes, int k,
                                    size_t li, ShadowQueue& queue) const {
  if (!lanes.contributes[k]) return;
  // queueSamples' shadow ray and term, from the point's sample worked out in lanes.
  const int q = queue.size;
  Ray& r = queue.rays[q];
  r.o = {lanes.o[0][k], lanes.o[1][k], lanes.o[2][k]};
  r.d = {lanes.d[0][k], lanes.d[1][k], lanes.d[2][k]};
  r.tMin = 0;
  r.tMax = kShadowRayEnd;
  r.time = pt.time;
  r.origin = ray_origin::light(li);
  const Vec3f wi{lanes.wi[0][k], lanes.wi[1][k], lanes.wi[2][k]};
  const Rgb intensity{lanes.intensity[0][k], lanes.intensity[1][k], lanes.intensity[2][k]};
  queue.term[q] = reflectedLight(pt.material->surface, pt.sp, pt.at, wi) * intensity;
  queue.atInfinity[q] = false;
  if (transparentShadows()) queue.media[q] = &pt.branch->media;
  queue.size = q + 1;
}

void BatchedKernel::flushShadows(Scratch& scratch, Generation::Sum* sums, AovSample* const* aovs,
                                 RayCounters& counters) const {
  traceShadows(scratch.queue, counters);
  addDirectLight(scratch, sums, aovs);
  scratch.queue.size = 0;
  scratch.queue.runCount = 0;
}

void BatchedKernel::addDirectLight(Scratch& scratch, Generation::Sum* sums,
                                   AovSample* const* aovs) const {
  const auto& queue = scratch.queue;
  for (int r = 0, begin = 0; r < queue.runCount; begin = queue.runs[r++].end) {
    const ShadowRun& run = queue.runs[r];
    if (run.point == ShadowRun::kEachRay) {
      // A delta light's: each ray its point's whole sample (a point whose sample was behind or
      // black has no ray, and adds nothing).
      for (int q = begin; q < run.end; ++q) {
        auto& p = scratch.pending[queue.pointOf[q]];
        *p.rays += tracedIn(queue, q, q + 1);
        AovSample* aov = aovs ? aovs[p.ray] : nullptr;
        addContribution(sumVisible(queue, q, q + 1), static_cast<size_t>(run.light),
                        sums[p.ray].local, aov ? aov->perLight : nullptr);
      }
      continue;
    }
    auto& p = scratch.pending[run.point];
    const Rgb sum = sumVisible(queue, begin, run.end, run.continues ? p.lightSum : Rgb{});
    *p.rays += tracedIn(queue, begin, run.end);
    if (!run.lastOfLight) {
      p.lightSum = sum;
      continue;
    }
    AovSample* aov = aovs ? aovs[p.ray] : nullptr;
    addContribution(sum, static_cast<size_t>(run.light), sums[p.ray].local,
                    aov ? aov->perLight : nullptr);
  }
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

template <class L>
void BatchedKernel::queueSamples(const LitPoint& pt, const L& light, size_t li,
                                 SubSampleStream* draws, int size, ShadowQueue& queue) const {
  constexpr bool delta = std::is_same_v<L, PointLight> || std::is_same_v<L, DirectionalLight>;
  constexpr bool atInfinity =
      std::is_same_v<L, DirectionalLight> || std::is_same_v<L, EnvironmentLight>;
  [[maybe_unused]] const uint32_t origin = ray_origin::light(li);
  // One ray of a delta light leaves from the side it needs; many rays pick one of two sides.
  [[maybe_unused]] const auto from = [&] {
    if constexpr (delta)
      return 0;
    else
      return ShadowOrigin(pt.sp);
  }();
  const int begin = queue.size;
  int q = begin;
  for (int j = 0; j < size; ++j) {
    const LightSample ls =
        sampleLight(light, pt.sp.p, pt.at.n, delta ? Vec2f{0.5f, 0.5f} : draws->next());
    if (!facesLight(pt.at, ls.wi) || ls.intensity.isBlack()) continue;
    const Rgb f = reflectedLight(pt.material->surface, pt.sp, pt.at, ls.wi);
    if constexpr (delta)
      spawnShadowRayInto(queue.rays[q], pt.sp, !atInfinity, atInfinity ? ls.wi : ls.target, pt.time,
                         li);
    else if constexpr (atInfinity)
      from.spawnAlong(queue.rays[q], ls.wi, pt.time, origin);
    else
      from.spawnTo(queue.rays[q], ls.target, pt.time, origin);
    queue.term[q] = f * ls.intensity;
    queue.atInfinity[q] = atInfinity;
    ++q;
  }
  queue.size = q;
  if (transparentShadows())
    std::fill(queue.media.data() + begin, queue.media.data() + q, &pt.branch->media);
}

void BatchedKernel::queueSamples(const LitPoint& pt, const EnvironmentLight& light, size_t li,
                                 SubSampleStream* draws, int size, ShadowQueue& queue) const {
  const ShadowOrigin from(pt.sp);
  const uint32_t origin = ray_origin::light(li);
  const int begin = queue.size;
  int q = begin;
  constexpr int kBlock = 64;
  // Written before they are read: zeroing them took a share of a sky's samples.
  UninitializedArray<Vec2f, kBlock> u;
  UninitializedArray<EnvironmentSample, kBlock> samples;
  for (int first = 0; first < size; first += kBlock) {
    const int block = std::min(kBlock, size - first);
    for (int j = 0; j < block; ++j) u[j] = draws->next();
    light.sample(pt.at.n, u.data(), block, samples.data());
    for (int j = 0; j < block; ++j) {
      const EnvironmentSample& s = samples[j];
      if (!facesLight(pt.at, s.wi) || s.radianceOverPdf.isBlack()) continue;
      const Rgb f = reflectedLight(pt.material->surface, pt.sp, pt.at, s.wi);
      from.spawnAlong(queue.rays[q], s.wi, pt.time, origin);
      queue.term[q] = f * s.radianceOverPdf;
      queue.atInfinity[q] = true;
      ++q;
    }
  }
  queue.size = q;
  if (transparentShadows())
    std::fill(queue.media.data() + begin, queue.media.data() + q, &pt.branch->media);
}

void BatchedKernel::traceShadows(ShadowQueue& queue, RayCounters& counters) const {
  const auto n = static_cast<size_t>(queue.size);
  // Shadows are see-through only where there are dielectrics to see through.
  if (transparentShadows()) {
    // Most shadow rays meet nothing: those are found as one coherent stream, as opaque shadows
    // are (Embree's packets, as for opaque shadows, where the walk below traces one ray), and
    // only the others walk through their interfaces one ray at a time. A miss from outside
    // every medium lets all the light through, as transparentShadow's first step does.
    accel_.occludedCoherent(queue.rays.data(), queue.blocked, n);
    for (size_t i = 0; i < n; ++i) {
      if (!queue.blocked[i] && queue.media[i]->empty()) {
        ++counters.shadow;
        queue.visible[i] = Rgb{1, 1, 1};
        queue.traced[i] = 1;
        continue;
      }
      const uint64_t before = counters.shadow;
      queue.visible[i] = transparentShadow(scene_, accel_, queue.rays[i], queue.atInfinity[i],
                                           *queue.media[i], minThroughput_, counters);
      queue.traced[i] =
          static_cast<uint32_t>(counters.shadow - before);  // at most kMaxShadowInterfaces + 1
    }
    return;
  }
  counters.shadow += n;
  // The queue is sorted by light (lightPendingPoints queues light by light): each light's rays,
  // which start close together and converge on it (or run parallel), are one coherent run of
  // the stream.
  accel_.occludedCoherent(queue.rays.data(), queue.blocked, n);
}

}  // namespace glint
