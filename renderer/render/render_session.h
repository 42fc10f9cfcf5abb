#pragma once
// One frame's render, pass by pass. A frame's life:
//
//   plan      the constructor makes the pass plan (render/pass_plan.h) and checks it before
//             anything is allocated: sample sets, memory, and a continued frame's state;
//   spread    an adaptive frame renders its probes' first pass to measure how much one sample
//             spreads over the frame (measureSpread; runPass does it when a pass needs it);
//   passes    each pass chooses its pixels (adaptive sampling, or a cut pass's kept choice),
//             renders them tile by tile (render/tile_pass.h) and updates their estimates;
//   the film  snapshot() resolves the frame as it stands (a preview, a partial); finish()
//             resolves the frame as written and its statistics.
//
// `glint render` (with its previews and interrupts), the Python module's Scene.render (pass by
// pass, for its progress callback) and renderScene (`glint bench`, `glint converge`, the tests)
// drive it the same way: construct, runPass() or runToEnd(), finish(). Every
// pass's result depends only on the state the passes before it left, so a frame driven pass by
// pass, snapshotted between passes, or continued from a snapshot's estimates and position gives the
// same bytes as one rendered straight through.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "accel/accelerator.h"
#include "camera/camera.h"
#include "core/interrupt.h"
#include "core/sampler.h"
#include "film/film.h"
#include "integrator/ray_counters.h"
#include "render/aov_accumulator.h"
#include "render/pass_plan.h"
#include "render/pixel_estimate.h"
#include "render/progress.h"
#include "render/render_job.h"
#include "render/resume_state.h"
#include "render/tile_pass.h"
#include "render/tile_scheduler.h"
#include "scene/scene.h"

namespace glint {

class RenderSession {
 public:
  // Plans the frame and checks it: throws UsageError where one pixel's set of samples is too
  // large (checkSampleSets), where the frame would not fit in memory (checkFrameFits), for AOVs
  // with the reference integrator, and where opt.resumeFrom cannot be continued by this plan
  // (a crop's adaptive apron, AOVs that need samples, passes that stopped off this plan's).
  // `scene`, `accel` and opt.cancel must outlive the session; opt.resumeFrom is read here only.
  // The time limit and the statistics' seconds count from here.
  RenderSession(const Scene& scene, const Accelerator& accel, const RenderOptions& opt);
  ~RenderSession();
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  const PassPlan& plan() const { return plan_; }
  // Whether the plan has passes left and no stop ended the frame.
  bool passesLeft() const { return !ended_ && next_ < plan_.ends.size(); }

  // Adaptive sampling: renders the probes' first pass and measures the frame's spread, unless
  // it is measured already or the plan is not adaptive. Returns false when a cancel cut it
  // short: the frame then ends, partial.
  bool measureSpread();
  // Takes the plan's next pass that samples any pixel (passes a continued frame finished, and
  // those no pixel needs, are passed over as finished). Returns true when it finished one;
  // false when no pass was left, or a stop cut the pass short: a cancel (the frame is partial)
  // or the time limit (passes from the second on stop at it; the frame is not partial).
  bool runPass();
  // Runs the passes until none is left or a stop; calls onPass with a snapshot after each that
  // finished but the last, between passes, inside the render's arena (PassCallback).
  void runToEnd(const PassCallback& onPass = {});

  // The passes finished so far, the last one's figures as of its end: for a driver's progress
  // between passes, without resolving the frame (snapshot()).
  const std::vector<PassRecord>& passesFinished() const { return stats_.passes; }

  // The frame as it stands: each pixel's finished passes resolved, the statistics as of the
  // last pass finished or cut, the estimates and position to continue it from, partial when a
  // cancel has cut it.
  RenderResult snapshot() const;
  // The frame as written: once, at the end; the session is spent after it. The frame is
  // partial when a cancel cut it, or when passes were left untaken.
  RenderResult finish();

 private:
  using Clock = std::chrono::steady_clock;

  // The plan and the pixels it covers, checked before anything is allocated (planFrame).
  struct Shape {
    PassPlan plan;
    PixelWindow window;         // the pixels written: the frame, or the crop
    PixelWindow sampledWindow;  // the window and the apron adaptive sampling needs around it
  };
  static Shape planFrame(const Scene& scene, const RenderOptions& opt);

  // The steps of the passes, each on the render's threads (arena_).
  bool takeNextPass();
  bool measureSpreadOnThreads();
  int64_t choosePixels(int end);
  bool renderChosen(int64_t pixels);
  // Renders one phase of tiles (a pass, or the probes) in the order of their expected cost,
  // noting its timing; returns whether a stop cut it short.
  bool renderTiles(const FrameContext& frame, const PassContext& pass,
                   const std::vector<PixelWindow>& tiles, std::vector<RayCounters>& counters,
                   Progress& progress, int spp);
  void passCut(int end);
  void passFinished(int end);
  // Brings stats_ up to the frame as it stands (rays, seconds, samples, estimated error);
  // returns the samples the window's pixels hold.
  int64_t refreshStats();
  const PixelEstimates& windowEstimates();

  // What the frame is made of, fixed by the constructor.
  const Scene& scene_;
  const Accelerator& accel_;
  const RenderOptions opt_;
  const RenderOptions probeOptions_;  // the probes': beauty only
  const Clock::time_point start_;
  // A stop asked for by a signal must be seen in bounded time, whatever the threads wait on;
  // until finish(). Only where the signal's flag is the cancel flag (`glint render`): another
  // driver (the Python module) keeps its process's signals and alarms as they are.
  std::optional<interrupt::Sampling> boundedStop_;
  const Shape shape_;
  const PassPlan& plan_ = shape_.plan;
  const int threads_, tileSize_;
  const ThreadArena arena_;  // the render's threads, for every step of its passes
  const std::vector<PixelWindow> tiles_;
  const Camera camera_;
  const CameraSampling cameraSampling_;
  const Sampler sampler_;
  Film aovSums_;
  const AovLayout aovLayout_;
  AovTables aovTables_;
  const std::unique_ptr<TilePasses> integrator_;
  Progress progress_;

  // What the passes change.
  PixelEstimates estimates_;      // per pixel of the sampled window, row-major
  std::vector<uint8_t> sampled_;  // the pixels the pass being taken chose
  ChoiceCache choiceCache_;
  std::optional<FrameSpread> spread_;
  PassPosition position_;                  // where the passes stand
  std::optional<PassPosition> resumedAt_;  // where the continued frame's stood
  size_t next_ = 0;                        // the plan's next pass
  std::vector<RayCounters> tileCounters_, probeCounters_;
  std::atomic<int> loggedNonfinite_{0};
  std::atomic<bool> deadlinePassed_{false};
  RenderStats stats_;
  PixelEstimates cropEstimates_;  // the window's, where an apron is sampled
  RenderTiming timing_;
  Clock::time_point phaseEnd_;  // when the last phase of tiles ended
  double loopSeconds_ = 0;      // in timedLoops since then
  bool summaryFresh_ = false;   // stats_ describes the pixels as they are (refreshStats)
  int64_t summarySamples_ = 0;

  // Runs `loops` (the loops over the frame's pixels between phases, on the render's threads),
  // adding their time to loopSeconds_.
  template <class Loops>
  void timedLoops(Loops&& loops) {
    const Clock::time_point begin = Clock::now();
    loops();
    loopSeconds_ += std::chrono::duration<double>(Clock::now() - begin).count();
  }
  bool partial_ = false;  // a cancel cut the frame short
  bool ended_ = false;    // a stop ended the frame
  bool finished_ = false;

  // The tiles' view of all the above.
  const FrameContext frame_;
};

}  // namespace glint
