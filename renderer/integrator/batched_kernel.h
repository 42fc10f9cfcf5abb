#pragma once
// The production integrator: seed 002 §9.1's recursive ray tracing, organised for speed.
// integrator/reference.h is the same algorithm written depth first, as plainly as the seed's
// pseudocode, and the oracle this kernel must match (tests/integrator/reference_test.cpp). This
// file owns only the order in which rays are traced and where their data live; what happens at
// a surface is decided in materials/ and what a light delivers in lights/.
// From a camera ray to a pixel, one named stage per queue (as pbrt-v4's wavefront integrator):
//  camera rays and their closest hits (traceCameraHits), then per chunk of rays of one depth
//  (shadeChunk): shadeHits (emission, ambient, the rays each hit spawns into the next
//  Generation, lit points into the pending list), lightPendingPoints (queueShadowRays light by
//  light, traceShadows as coherent streams, addDirectLight), traceGeneration (the spawned rays
//  traced as one coherent stream and shaded) and sumRadiance (each ray's local light plus its
//  children's).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/accelerator.h"
#include "core/check.h"
#include "core/rgb.h"
#include "core/sampler.h"
#include "core/uninitialized_array.h"
#include "integrator/aov.h"
#include "integrator/footprint.h"
#include "integrator/medium_stack.h"
#include "integrator/radiance.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

struct PointLightLanes;

class BatchedKernel {
 public:
  // `footprintSpp`: the samples each pixel's footprint is shared among (pixelCone); a render
  // chooses it (PassPlan::footprintSpp).
  BatchedKernel(const Scene& scene, const Accelerator& accel, float minThroughput,
                int footprintSpp);

  // Where a thread keeps a chunk's pending lit points, their shadow rays and the rays each
  // generation spawns: one per thread, reused for every chunk.
  struct Scratch;

  // Radiance along `count` camera rays whose closest hits are known (traced together as a
  // coherent stream, Accelerator::intersectCoherent), samples keys[i]: runs of consecutive
  // samples of one half of one or several pixels, as renderTilePass makes them. aovs, when given,
  // holds a record pointer (or null) per sample, whose viewAxis must be set (the camera's unit view
  // direction, for depth); the record receives what the camera ray hit. out[i] does not depend on
  // which other samples share the call, bit for bit.
  void traceCameraHits(const Ray* rays, const Hit* hits, const SampleKey* keys, int count,
                       Radiance* out, AovSample* const* aovs, RayCounters& counters,
                       Scratch& scratch) const;
  // One sample on its own (tests and tools): traceCameraHits for one ray.
  Radiance trace(const Ray& cameraRay, const SampleKey& key, RayCounters& counters,
                 AovSample* aov = nullptr) const;

 private:
  static constexpr int kChunk = 64;  // rays of one generation shaded together

  struct Branch {  // what travels with a ray down the tree of reflections and refractions
    int depth = 0;
    Rgb share{1, 1, 1};  // of the sample (branchShare), which the cutoff reads
    const SampleKey* key = nullptr;
    float distance = 0;  // travelled from the eye to the ray's origin (the pixel's cone)
    // Last: a ray outside every dielectric writes and reads only the stack's size, in the
    // same cache line as the fields above.
    MediumStack media;
  };

  // The rays that one chunk of a generation spawns, and what the chunk keeps about its own
  // rays while they are traced. A ray's radiance is (local + Σ weight · child radiance) ·
  // absorbed, its children in the order spawned (seed 002 §9.1: reflection, then refraction).
  struct Generation {
    static constexpr int kCapacity = kMaxCoherentRays * kChunk;
    // Per ray of the chunk, what its sum needs, in one cache line: in a deep chain of mirrors
    // these leave L1 before the sum is taken, and as separate arrays each ray missed four lines.
    struct Sum {
      Rgb local;     // the light it returns before its children's (emission, ambient, direct)
      Rgb absorbed;  // Beer's attenuation of the segment it travelled, where inMedium
      int childEnd;  // one past its last child
      bool inMedium;
    };
    Sum sums[kChunk];
    // The children, written before they are read.
    UninitializedArray<Ray, kCapacity> rays;
    UninitializedArray<Hit, kCapacity> hits;
    UninitializedArray<Branch, kCapacity> branches;
    UninitializedArray<Rgb, kCapacity> weight;  // what the parent multiplies its radiance by
    UninitializedArray<Rgb, kCapacity> radiance;
    int children = 0;

    // A child of `parent` with weight w and `share` of the sample in `media`; returns its
    // ray's slot for the caller to write. Written in place: a Branch built in a temporary and
    // copied in was reloaded before its stores had landed (store forwarding).
    Ray& add(const Branch& parent, const Rgb& w, const Rgb& share, const MediumStack& media,
             float distance) {
      Branch& b = branches[children];
      b.depth = parent.depth + 1;
      b.distance = distance;
      b.share = share;
      b.media.assign(media);
      b.key = parent.key;
      weight[children] = w;
      return rays[children++];
    }
  };

  // Radiance along `n` (at most kChunk) rays of one depth, given their closest hits, into
  // radiance[i]. aovs: at the camera only.
  void shadeChunk(const Ray* rays, const Hit* hits, const Branch* branches, int n, Rgb* radiance,
                  AovSample* const* aovs, RayCounters& counters, Scratch& scratch) const;
  // shadeChunk's first stage: each ray's local light (background past the depth limit or on a
  // miss; else emission and ambient), its children spawned into `gen`, and its hit, where the
  // surface reflects the lights, added to the pending list (lit first when the queue is full).
  void shadeHits(const Ray* rays, const Hit* hits, const Branch* branches, int n, Generation& gen,
                 AovSample* const* aovs, RayCounters& counters, Scratch& scratch) const;
  // The rays `gen` holds, spawned by a chunk of depth `depth`: traced as one coherent stream
  // and shaded a chunk at a time, into gen.radiance.
  void traceGeneration(Generation& gen, int depth, RayCounters& counters, Scratch& scratch) const;
  // Each of the n rays' radiance: (local + Σ weight · child radiance) · absorbed, children in
  // the order spawned, the order the depth-first recursion sums in.
  static void sumRadiance(const Generation& gen, int n, Rgb* radiance);
  // The generation that the chunks of depth `depth` spawn into (made on first use).
  Generation& generation(Scratch& scratch, int depth) const;
  // Spawns into `gen` the rays the material at a hit sends on (materials' forEachCoherentRay),
  // each that its share keeps, for `ray` arriving along unit d: the interior list goes
  // with a refracted ray across the surface; `u` spreads a glossy or blurred lobe. Counts the
  // traced ones in `sampleRays`. Called only for a material that refracts or reflects
  // coherently.
  void spawnCoherent(const Hit& hit, const Material& m, const ShadingPoint& sp,
                     const SurfacePoint& at, const Ray& ray, const Vec3f& d, const Branch& branch,
                     float distance, const LobeSamples& u, Generation& gen, RayCounters& counters,
                     uint64_t& sampleRays) const;
  // How far a ray's pixel cone has come at its hit (image textures only; else 0).
  float distanceAt(const Ray& ray, const Hit& hit, const Branch& branch) const {
    return scene_.features.surfaceCoordinates ? branch.distance + hit.t * length(ray.d) : 0;
  }

  // A hit whose surface reflects the lights (materials' reflectsLights), waiting for its
  // direct light: AccLightSource's loop, run for many points at once.
  struct LitPoint {
    const Material* material = nullptr;
    ShadingPoint sp;
    SurfacePoint at;
    float time = 0;
    const Branch* branch = nullptr;
  };
  // A run of the shadow queue: samples of one light at one pending point, in sample order. A
  // point's samples of a light that outnumber the queue's room are split over runs of several
  // tracings. A delta light's one sample per point is a run of its own light's rays at many
  // points instead, each ray naming its point (ShadowQueue::pointOf): a run per point and sample
  // cost more than the sample.
  struct ShadowRun {
    int point;  // its index in the pending list; kEachRay: a delta light's run
    int light;
    int end;           // one past its last ray in the queue; it begins where the previous ends
    bool continues;    // the light's samples at the point began in an earlier tracing
    bool lastOfLight;  // its light's samples at the point are all queued: the light's sum is whole
    static constexpr int kEachRay = -1;
  };
  // One shadow ray per light sample that can contribute, with what it adds unblocked, in runs.
  // Slots [0, size) are written by queueSamples and traceShadows before anything reads them.
  struct ShadowQueue {
    static constexpr int kCapacity = 512;
    // Full when either is: a run can be empty (every sample behind the surface).
    bool full() const { return size == kCapacity || runCount == kCapacity; }
    void addRun(int point, int light, bool continues, bool lastOfLight) {
      runs[runCount++] = {point, light, size, continues, lastOfLight};
    }
    UninitializedArray<ShadowRun, kCapacity> runs;
    int runCount = 0;
    UninitializedArray<Ray, kCapacity> rays;
    UninitializedArray<Rgb, kCapacity> term;  // reflected light · intensity: what it adds unblocked
    bool atInfinity[kCapacity];
    // Where each ray starts: the interior list of its point's ray (transparent shadows).
    UninitializedArray<const MediumStack*, kCapacity> media;
    UninitializedArray<int, kCapacity> pointOf;  // in a delta light's run, each ray's point
    int size = 0;
    // Filled by traceShadows: whether each ray meets anything; with transparent shadows
    // (transparentShadows()) also the fraction of the light arriving.
    bool blocked[kCapacity];
    UninitializedArray<Rgb, kCapacity> visible;
    // With transparent shadows, the rays each one took (one per stretch between interfaces);
    // an opaque shadow is one ray.
    UninitializedArray<uint32_t, kCapacity> traced;
  };
  // The rays queued samples [begin, end) traced (Radiance::rays).
  uint64_t tracedIn(const ShadowQueue& queue, int begin, int end) const {
    if (!transparentShadows()) return static_cast<uint64_t>(end - begin);
    uint64_t n = 0;
    for (int q = begin; q < end; ++q) n += queue.traced[q];
    return n;
  }
  bool transparentShadows() const { return scene_.render.transparentShadows; }
  // Queues `size` samples of `light` (light li, of type L) at the point, each u drawn from
  // `draws` (a delta light draws none: then `size` is 1), except those from behind the surface
  // or black: per sample the shadow ray and what the light adds if it is not blocked. The type
  // is known here, so that what depends only on the point or the light (the shadow rays' origin
  // on both sides of the surface) is done once for the samples, and a sample never passes
  // through memory on its way from sampleLight.
  template <class L>
  void queueSamples(const LitPoint& pt, const L& light, size_t li, SubSampleStream* draws, int size,
                    ShadowQueue& queue) const;
  // queueSamples for an environment: its samples drawn a block at a time, so that the light
  // finds a block's table cells before their directions (EnvironmentLight::sample's block form).
  void queueSamples(const LitPoint& pt, const EnvironmentLight& light, size_t li,
                    SubSampleStream* draws, int size, ShadowQueue& queue) const;
  // The direct light of the points pending in the scratch, added to their ray's local:
  // queueShadowRays, traceShadows, addDirectLight. Empties the pending list and the queue.
  void lightPendingPoints(Scratch& scratch, typename Generation::Sum* sums, AovSample* const* aovs,
                          RayCounters& counters) const;
  // Light li's samples at every pending point queued as runs, the queue traced and its light
  // added (flushShadows) whenever it is full; queueShadowRaysOf once the light's type is known.
  void queueShadowRays(Scratch& scratch, size_t li, Generation::Sum* sums, AovSample* const* aovs,
                       RayCounters& counters) const;
  template <class L>
  void queueShadowRaysOf(Scratch& scratch, const L& light, size_t li, Generation::Sum* sums,
                         AovSample* const* aovs, RayCounters& counters) const;
  // queueSamples for point k of a point light that is not a spot, from its sample worked out
  // with the other pending points' in lanes (integrator/point_light_lanes.h): the same bits.
  void queueLaneSample(const LitPoint& pt, const PointLightLanes& lanes, int k, size_t li,
                       ShadowQueue& queue) const;
  // Whether each queued shadow ray is blocked (or, with transparent shadows, what it lets
  // through).
  void traceShadows(ShadowQueue& queue, RayCounters& counters) const;
  // The traced queue's runs summed into their point's light sums; a light's whole sum added to
  // its point's local light.
  void addDirectLight(Scratch& scratch, Generation::Sum* sums, AovSample* const* aovs) const;
  // traceShadows then addDirectLight; empties the queue.
  void flushShadows(Scratch& scratch, Generation::Sum* sums, AovSample* const* aovs,
                    RayCounters& counters) const;
  // `sum` plus what queued samples [begin, end) let through, added in queue order. Inlined: a
  // delta light's range is one sample, and as a call its sum went through memory.
  [[gnu::always_inline]] Rgb sumVisible(const ShadowQueue& queue, int begin, int end,
                                        Rgb sum = {}) const {
    if (transparentShadows()) {
      for (int q = begin; q < end; ++q)
        if (!queue.visible[q].isBlack()) sum += queue.term[q] * queue.visible[q];
    } else {
      for (int q = begin; q < end; ++q)
        if (!queue.blocked[q]) sum += queue.term[q];
    }
    return sum;
  }
  // Light li's share (the mean over its samples, `sum` their total) added to L, and kept in
  // perLight[li] when given (per-light AOVs).
  void addContribution(const Rgb& sum, size_t li, Rgb& L, Rgb* perLight) const {
    const Rgb contribution = meanOverSamples(sum, lights_[li].samples);
    L += contribution;
    if (perLight && li < size_t(AovSet::kMaxLights)) perLight[li] = contribution;
  }
  // Per light, what the loops over lights ask of it, looked up once rather than of the variant
  // per light and point: its shadow samples per point and whether it is a delta light (one
  // shadow ray, no sample drawn).
  struct LightInfo {
    int samples;
    bool delta;
  };
  SamplePattern lightPattern(const LitPoint& pt, size_t li) const;
  void recordAov(const Ray& ray, const Hit& hit, const Material& m, const ShadingPoint& sp,
                 const SurfacePoint& at, AovSample& aov) const;

  const Scene& scene_;
  const Accelerator& accel_;
  float minThroughput_;
  PixelCone cone_;
  std::vector<LightInfo> lights_;
  // Per material, what shadeHits asks at every hit, decided once: asked of the material, each is
  // a test of its textures' kinds and constants.
  struct MaterialFlags {
    bool reflectsLights;  // materials' reflectsLights: the point waits for its direct light
    bool spawnsRays;      // it refracts or reflects coherently: forEachCoherentRay may send rays
    bool drawsLobes;      // materials' drawsLobeSamples: a glossy or blurred lobe's sample
  };
  std::vector<MaterialFlags> materials_;
  bool drawsLobes_ = false;  // some material draws lobe samples (materials' drawsLobeSamples)
  int64_t shadowRaysPerPoint_ = 0;  // at most, over all lights: what a lit point may queue

 public:
  struct Scratch {
    // The lit points of a chunk whose direct light is still to be found.
    struct Pending {
      LitPoint pt;
      int ray = 0;               // its ray's index in the chunk
      Rgb lightSum;              // a light's samples so far, where they span tracings
      uint64_t* rays = nullptr;  // where its camera sample counts the shadow rays traced for it
    };
    Pending pending[kChunk];
    int pendingCount = 0;
    ShadowQueue queue;
    Branch roots[kChunk];
    Rgb cameraRadiance[kChunk];
    // The rays each camera sample of the chunk being shaded has traced beyond its camera ray
    // (Radiance::rays), by the index of its branches' key in rootKeys.
    uint64_t raysOf[kChunk];
    const SampleKey* rootKeys = nullptr;
    int rootCount = 0;
    uint64_t& raysOfRoot(const Branch& b) {
      // Every branch descends from one of the rootCount camera samples of the chunk being
      // shaded; one compare per branch, negligible next to tracing its rays.
      const std::ptrdiff_t root = b.key - rootKeys;
      GLINT_CHECK(root >= 0 && root < rootCount);
      return raysOf[root];
    }
    // generations[d]: the rays of depth d + 1, spawned by a chunk of depth d.
    std::vector<std::unique_ptr<Generation>> generations;
  };
};

}  // namespace glint
