#pragma once
// Renders a scene into a film: camera samples per pixel through the integrator, box filter,
// non-finite samples counted and dropped, tiles on all cores, progress on stderr. The samples
// come in passes (render/pass_plan.h), after each of which the frame knows its estimated error.
#include <algorithm>
#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "camera/camera.h"
#include "core/sampler.h"
#include "core/uninitialized_array.h"
#include "film/film.h"
#include "integrator/aov.h"
#include "integrator/radiance.h"
#include "integrator/ray_counters.h"
#include "render/pass_plan.h"
#include "render/pass_timing.h"
#include "render/resume_state.h"
#include "render/tile_scheduler.h"
#include "scene/scene.h"

namespace glint {

enum class IntegratorKind { Production, Reference };
bool parseIntegratorKind(const std::string& name, IntegratorKind& out);

struct RenderOptions {
  int threads = 0;    // 0 = all cores
  int tileSize = 32;  // an upper bound: see effectiveTileSize
  TileOrder tileOrder = TileOrder::Morton;
  std::optional<PixelWindow> crop;  // default: the full frame
  bool progress = true;
  // When set to true (by a signal handler), each thread stops after its chunk of samples in
  // flight, and the result is marked partial. A pixel keeps the passes it finished; one that
  // finished none stays at zero, alpha 0.
  const std::atomic<bool>* cancel = nullptr;
  // Adaptive sampling, a time limit, bounds on a pixel's samples (render/pass_plan.h).
  SamplingRequest sampling;
  // The state a render of the same frame and settings left (render/resume_state.h): its
  // pixels go on from there, and its passes from where they stood. Null: from nothing.
  const ResumeState* resumeFrom = nullptr;
  AovSet aovs;  // none by default
  // Whether the frame is taken between passes (runToEnd's callback: previews), each time a
  // copy of its states and film written with them: counted when the session checks that the
  // frame fits in memory.
  bool previews = false;
  // Whether each tile's thread CPU time is noted in RenderStats::timing besides its wall time
  // (a system call per tile: only for `--stats-json`).
  bool tileCpuTimes = false;
  // The production kernel (integrator/batched_kernel.h), or its oracle, the depth-first
  // reference integrator (integrator/reference.h: `--integrator reference`, beauty only).
  IntegratorKind integrator = IntegratorKind::Production;
  // Test hook: sees (and may alter) every camera sample before it reaches the film, so tests
  // can force a NaN through the real path. Never set in production.
  std::function<void(int x, int y, Radiance& sample)> sampleHook;
};

// Camera rays are made, traced and shaded in chunks of at most this many samples (bounded
// stack arrays): several whole pixels' below this spp, a run of one pixel's from it on.
inline constexpr int kCameraChunk = 64;

// A camera sample's ray, shared by the render loop and `glint bench`'s sampling pass: the pixel
// offset always; the lens and shutter-time dimensions only when the camera has a lens or
// something moves under an open shutter (leave out what is not needed).
class CameraSampling {
 public:
  CameraSampling(const Scene& scene, const Camera& camera)
      : camera_(camera),
        open_(scene.cameraDesc.shutterOpen),
        close_(scene.cameraDesc.shutterClose),
        openShutter_(scene.features.motion && close_ > open_) {}

  // Where rays() keeps a chunk's sets and points: one per tile or thread. Declared inside
  // rays(), the arrays were cleared per call (a `rep stos` that a 1-spp render paid per camera
  // ray).
  struct Points {
    static constexpr int kDims = 3;  // pixel, lens, time
    // Each pixel half's set of each dimension in the chunk, made once for all its samples.
    UninitializedArray<SamplePattern, kCameraChunk> sets[kDims];
    // Per point, in the order drawn: its set, its index in the set, its sample in the chunk.
    const SamplePattern* at[kDims][kCameraChunk];
    uint32_t flat[kCameraChunk];
    int sample[kCameraChunk];
    UninitializedArray<Vec2f, kCameraChunk> points[kDims];
  };
  // The rays of `count` samples, any pixels' and halves', into out, where the keys of one
  // pixel half's samples stand next to each other. A chunk's points of a dimension are drawn
  // side by side, several pixels' sets in one block of lanes (Sampler::get2DAt): at low spp a
  // pixel half adds one or two samples a pass, which drawn apart paid for a block each.
  void rays(const SampleKey* keys, int count, Ray* out, Points& points) const {
    for (int first = 0; first < count; first += kCameraChunk)
      chunkRays(keys + first, std::min(kCameraChunk, count - first), out + first, points);
  }

 private:
  void chunkRays(const SampleKey* keys, int count, Ray* out, Points& points) const;

  const Camera& camera_;
  float open_, close_;
  bool openShutter_;
};

// One finished pass: where the frame stood when it ended.
struct PassRecord {
  int spp = 0;            // the samples per pixel the pass brought pixels up to
  double meanSpp = 0;     // the samples per pixel taken so far, averaged over the frame
  double seconds = 0;     // since the render began
  FrameError estimated;   // the frame's estimated error after the pass
  int64_t pixelsSampled;  // the pixels the pass added samples to
};

struct RenderStats {
  double seconds = 0;
  RayCounters rays;
  IntegratorKind integrator = IntegratorKind::Production;
  SamplerKind sampler = SamplerKind::Stratified;  // the one used (PassPlan::sampler)
  std::vector<PassRecord> passes;                 // the finished ones
  FrameError estimated;                           // of the frame as written
  int minPixelSpp = 0, maxPixelSpp = 0;           // the fewest and most samples of a pixel
  bool timeLimitReached = false;                  // a pass was cut short by --time-limit
  RenderTiming timing;                            // the passes' phases (pass_timing.h)
};

struct RenderResult {
  Film film;
  RenderStats stats;
  bool partial = false;      // cancelled before every pixel had the samples the plan gave it
  int tileSize = 0;          // the effective tile edge
  PixelEstimates estimates;  // each pixel's state, to resume from
  PassPosition position;     // where the passes stood, to resume from
};

// Throws UsageError, naming the numbers and the light, when one pixel's set of samples (`spp`,
// the most a pixel may take, or spp × an area light's samples) is larger than kMaxSampleSet
// (core/sampler.h). The loader bounds spp alone; the product needs the light and a --spp or
// --max-spp override, so a render session checks it before anything renders.
void checkSampleSets(const Scene& scene, int64_t spp);

// Throws UsageError when a frame of `pixels` pixels of `bytesPerPixel` bytes each at the peak
// (the film, the pixels' states, the AOVs and the copies made to write them; `parts` says
// which, for the message) would not fit in `availableBytes`. Without this check an oversized
// frame was accepted and killed by the kernel when its film was first touched. availableBytes
// 0 means unknown: no check.
void checkFrameFits(int64_t pixels, size_t bytesPerPixel, uint64_t availableBytes,
                    const std::string& parts = {});

// Called after each finished pass with the frame so far (its film resolved, its stats up to
// that pass): previews. Runs on the calling thread, between passes, inside the render's arena
// (ThreadArena): TBB work it starts shares the render's threads.
using PassCallback = std::function<void(const RenderResult& soFar)>;

// A frame straight through: a RenderSession (render/render_session.h) run to its end.
RenderResult renderScene(const Scene& scene, const Accelerator& accel, const RenderOptions& opt,
                         const PassCallback& onPass = {});

}  // namespace glint
