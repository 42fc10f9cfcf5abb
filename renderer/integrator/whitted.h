#pragma once
// Recursive ray tracing of seed 002 §9.1 Trace(r, d): local Phong / Blinn-Phong shading with
// ambient light and shadows (optionally transparent), ideal mirror reflection, and dielectrics
// with Fresnel, total internal reflection, Beer's law and nesting. Materials are dispatched
// here and nowhere else. The recursion runs breadth first, a generation of rays at a time
// (shadeChunk), so that rays of one depth are traced together and their shading overlaps.
#include <memory>
#include <type_traits>
#include <vector>

#include "accel/accelerator.h"
#include "core/rgb.h"
#include "core/sampler.h"
#include "core/uninitialized_array.h"
#include "integrator/aov.h"
#include "integrator/kernel_caps.h"
#include "integrator/medium_stack.h"
#include "integrator/optics.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

// A branch whose throughput falls below this in every channel is not traced: it could change
// its pixel by at most this much times the radiance behind it (docs/shading.md).
inline constexpr float kDefaultMinThroughput = 1.0f / 1024.0f;

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
      : scene_(scene), accel_(accel), minThroughput_(minThroughput) {
    for (const Light& light : scene.lights) shadowRaysPerPoint_ += sampleCount(light);
    if constexpr (kMedia) {
      for (const NamedMaterial& m : scene.materials) {
        const auto* d = std::get_if<DielectricMaterial>(&m.material);
        media_.push_back(d ? BeerMedium(d->attenuation) : BeerMedium());
      }
    }
  }

  // Where traceCameraHits keeps a chunk's pending shading points, their shadow rays, the
  // area lights' points, and the rays each generation spawns: one per thread or tile, reused
  // for every chunk.
  struct Scratch;

  // Radiance along `count` camera rays whose closest hits are known (traced together as a
  // coherent stream, Accelerator::intersectCoherent), samples keys[i]: runs of consecutive
  // samples of one or several pixels, as renderTile makes them. aovs, when given (only where
  // Caps has cap::kAovs), holds a record pointer (or null) per sample, whose viewAxis must be
  // set (the camera's unit view direction, for depth); the record receives what the camera
  // ray hit. The work runs generation by generation (see shadeChunk): out[i] does not depend
  // on which other samples share the call, bit for bit.
  void traceCameraHits(const Ray* rays, const Hit* hits, const SampleKey* keys, int count,
                       Radiance* out, AovSample* const* aovs, RayCounters& counters,
                       Scratch& scratch) const;
  // One sample on its own (tests and tools): traceCameraHits for one ray.
  Radiance trace(const Ray& cameraRay, const SampleKey& key, RayCounters& counters,
                 AovSample* aov = nullptr) const;
  Radiance trace(const Ray& cameraRay, const Hit& cameraHit, const SampleKey& key,
                 RayCounters& counters, AovSample* aov = nullptr) const;

 private:
  static constexpr bool kMedia = (Caps & cap::kDielectrics) != 0;
  static constexpr bool kAreaLights = (Caps & cap::kAreaLights) != 0;
  static constexpr bool kGloss = (Caps & cap::kGloss) != 0;
  static constexpr bool kAovs = (Caps & cap::kAovs) != 0;
  static constexpr int kChunk = 64;  // rays of one generation shaded together

  // Without dielectrics a ray is always in the outside world: no interior list to carry.
  struct NoMedia {
    bool empty() const { return true; }
    void assign(const NoMedia&) {}
  };
  using Media = std::conditional_t<kMedia, MediumStack, NoMedia>;

  struct Branch {  // what travels with a ray down the tree of reflections and refractions
    int depth = 0;
    Rgb throughput{1, 1, 1};
    const SampleKey* key = nullptr;
    // Last: a ray outside every dielectric writes and reads only the stack's size, in the
    // same cache line as the fields above.
    [[no_unique_address]] Media media;
  };

  // The rays that one chunk of a generation spawns, and what the chunk keeps about its own
  // rays while they are traced. A ray's radiance is (local + Σ weight · child radiance) ·
  // absorbed, its children in the order spawned (seed 002 §9.1: reflection, then refraction).
  struct Generation {
    static constexpr int kCapacity = 2 * kChunk;  // a dielectric spawns two
    // Per ray of the chunk, what its sum needs, in one cache line: its sum is taken after
    // every generation below it has been traced, and in a deep chain of mirrors these had left
    // L1 by then, four lines per ray when they were four arrays (a quarter of shadeChunk's
    // samples in a box of mirrors 1000 bounces deep sat on one of those loads).
    struct Sum {
      Rgb local;     // the light it returns before its children's (ambient and direct light)
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

    // A child of `parent` with weight w (its throughput parent.throughput · w) in `media`;
    // returns its ray's slot for the caller to write. Written in place: a Branch built in a
    // temporary and copied in was reloaded before its stores had landed (a stall that perf
    // put at two thirds of the copy's time).
    Ray& add(const Branch& parent, const Rgb& w, const Rgb& throughput, const Media& media) {
      Branch& b = branches[children];
      b.depth = parent.depth + 1;
      b.throughput = throughput;
      b.media.assign(media);
      b.key = parent.key;
      weight[children] = w;
      return rays[children++];
    }
  };

  // Radiance along `n` (at most kChunk) rays of one depth, given their closest hits, into
  // radiance[i]. In stages over all of them, so that their independent chains of work run
  // side by side: each hit's shading point and the rays it spawns; the direct light of all the
  // Phong hits, their shadow rays traced together (lightPendingPoints); then the spawned rays
  // traced as one stream and shaded as the next generation, recursively; then each ray's sum.
  // aovs: at the camera only. cameraKeys: at the camera only, the samples' keys, from which an
  // area light's points for the whole chunk are drawn at once.
  void shadeChunk(const Ray* rays, const Hit* hits, const Branch* branches, int n, Rgb* radiance,
                  AovSample* const* aovs, const SampleKey* cameraKeys, RayCounters& counters,
                  Scratch& scratch) const;
  // The generation that the chunks of depth `depth` spawn into (made on first use).
  Generation& generation(Scratch& scratch, int depth) const;

  // Direct lighting of Phong surfaces (seed 000 eq. 4.4) runs in three steps, so that the
  // shadow rays of many shading points can be traced together: queueLight draws a light's
  // samples and queues one shadow ray per sample that could contribute, with what it adds if
  // unblocked; traceShadows finds what each ray lets through; sumVisible sums that per light.
  struct PhongPoint {
    const PhongMaterial* material = nullptr;
    ShadingPoint sp;
    Vec3f wo, n;  // unit, towards the viewer; the shading normal on the viewer's side
    Rgb kd;
    float time = 0;
    const Branch* branch = nullptr;
  };
  // Slots [0, size) are written by queueLight (all but the last two) and traceShadows before
  // anything reads them, so the arrays start uninitialised.
  template <int Capacity>
  struct ShadowQueue {
    static constexpr int kCapacity = Capacity;
    UninitializedArray<Ray, Capacity> rays;
    UninitializedArray<Rgb, Capacity> term;  // f · intensity: what the sample adds unblocked
    bool atInfinity[Capacity];
    int size = 0;
    // Filled by traceShadows: with opaque shadows whether each ray is blocked; with transparent
    // ones (transparentShadows()) the fraction of the light arriving.
    bool blocked[Capacity];
    UninitializedArray<Rgb, Capacity> visible;
  };
  bool transparentShadows() const { return kMedia && scene_.render.transparentShadows; }
  // Fills everything in `pt` but its shading point, which must be set (in place: see
  // Scene::shadingPoint).
  void initPhongPoint(PhongPoint& pt, const PhongMaterial& m, const Vec3f& wo, float time,
                      const Branch& branch) const;
  // The ambient term: where the light sums start.
  Rgb ambient(const PhongPoint& pt) const;
  // Queues samples [first, first + size) of light `li`'s `count` (pattern: its sample set;
  // `points`, when given: the set's points for this shading point, drawn already).
  template <class Queue>
  void queueLight(const PhongPoint& pt, size_t li, const SamplePattern& pattern, int first,
                  int size, int count, Queue& queue, const Vec2f* points = nullptr) const;
  // For a camera chunk: the points of the area lights among the first kMaxPrecomputedLights
  // for the `count` camera samples of `keys` (runs of consecutive samples of a pixel), into
  // the scratch; lightPointsOf[li] stays null for a delta light or one that no longer fits.
  static constexpr size_t kMaxPrecomputedLights = 8;
  void drawLightPoints(const SampleKey* keys, int count, Scratch& scratch) const;
  template <class Queue>
  void traceShadows(Queue& queue, RayCounters& counters) const;
  // The direct light of the shading points pending in the scratch, added to their ray's local:
  // every light's samples queued, light by light, the queue traced, the sums taken. `camera`:
  // they are camera hits (their area lights' points may be drawn already). Empties both.
  void lightPendingPoints(Scratch& scratch, typename Generation::Sum* sums, AovSample* const* aovs,
                          bool camera, RayCounters& counters) const;
  // `sum` plus what queued samples [begin, end) let through, added in queue order. Inlined: a
  // delta light's range is one sample, and as a call its sum went through memory.
  template <class Queue>
  [[gnu::always_inline]] Rgb sumVisible(const Queue& queue, int begin, int end,
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
  // Light li's share of a shading point, the mean over its samples (`sum` their total), added
  // to L, and kept in perLight[li] when given (per-light AOVs).
  void addContribution(const Rgb& sum, size_t li, Rgb& L, Rgb* perLight) const {
    const int count = sampleCount(scene_.lights[li]);
    const Rgb contribution = count == 1 ? sum : sum * (1.0f / static_cast<float>(count));
    L += contribution;
    if (perLight && li < size_t(AovSet::kMaxLights)) perLight[li] = contribution;
  }
  int sampleCount(const Light& light) const { return kAreaLights ? lightSampleCount(light) : 1; }
  static bool isDelta(const Light& light) {
    return !kAreaLights || std::holds_alternative<PointLight>(light) ||
           std::holds_alternative<DirectionalLight>(light);
  }
  SamplePattern lightPattern(const PhongPoint& pt, size_t li) const;
  // Ambient and direct light at a shading point whose shadow rays outnumber the shared queue:
  // its lights are traced on their own, a few samples at a time. `perLight`, when given,
  // receives each light's contribution (AOVs of the camera hit).
  Rgb shadePhongAlone(PhongPoint& pt, RayCounters& counters, Rgb* perLight) const;
  void recordAov(const Ray& ray, const Hit& hit, const ShadingPoint& sp, const Material& material,
                 AovSample& aov) const;
  // Fraction of a light's intensity that reaches sp along the shadow ray: 0 or 1, or with
  // transparent shadows the product of the dielectric transmissions met on the way.
  // `shadow` is the first segment, as spawned from the shading point.
  Rgb shadowTransmission(Ray shadow, bool atInfinity, RayCounters& counters) const;
  // Spawn into `gen` the rays a surface sends on, where they are traced at all: the mirror
  // ray of reflectance km (seed 000 §4.8, glossy §13.4.4), or a dielectric's reflected and
  // refracted rays (Fresnel, total internal reflection, nesting).
  void spawnReflection(const Rgb& km, float gloss, const ShadingPoint& sp, const Ray& ray,
                       const Branch& branch, Generation& gen, RayCounters& counters) const;
  void spawnDielectric(const Hit& hit, const DielectricMaterial& m, const ShadingPoint& sp,
                       const Ray& ray, const Branch& branch, Generation& gen,
                       RayCounters& counters) const;
  float iorOutside(const MediumStack& media) const;
  const DielectricMaterial* dielectric(uint32_t materialId) const;

  const Scene& scene_;
  const Accelerator& accel_;
  float minThroughput_;
  int shadowRaysPerPoint_ = 0;     // at most, over all lights: what a Phong point may queue
  std::vector<BeerMedium> media_;  // per material: what a dielectric's inside absorbs

 public:
  struct Scratch {
    // The Phong points of a chunk whose direct light is still to be found.
    struct Pending {
      PhongPoint pt;
      int ray = 0;  // its ray's index in the chunk
    };
    Pending pending[kChunk];
    int pendingCount = 0;
    ShadowQueue<512> queue;
    std::vector<uint16_t> rayEnd;                 // lightPendingPoints' ranges of the queue
    static constexpr int kMaxLightPoints = 2048;  // 64 samples × 32 points, for example
    Vec2f lightPoints[kMaxLightPoints];
    const Vec2f* lightPointsOf[kMaxPrecomputedLights] = {};  // per light; null: per point
    bool lightPointsDrawn = false;
    Branch roots[kChunk];
    Rgb cameraRadiance[kChunk];
    // generations[d]: the rays of depth d + 1, spawned by a chunk of depth d.
    std::vector<std::unique_ptr<Generation>> generations;
  };
};

using WhittedIntegrator = WhittedKernel<cap::kAll>;

}  // namespace glint
