#include "app/intersection_share.h"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "accel/ray_recorder.h"
#include "app/render_bench.h"
#include "render/render_job.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

// CPU seconds of the calling thread: what other processes on a shared machine take from it
// between two readings is not counted, as wall time would count it.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// `work` run on this thread alone (a one-thread arena, so that every parallel loop inside runs
// here too), in CPU seconds.
template <class Work>
double oneThreadCpuSeconds(Work&& work) {
  double seconds = 0;
  withThreads(1, [&] {
    const double start = threadCpuSeconds();
    work();
    seconds = threadCpuSeconds() - start;
  });
  return seconds;
}

RenderResult renderOneThread(const Scene& scene, const Accelerator& accel) {
  RenderOptions opt;
  opt.threads = 1;
  opt.progress = false;
  return renderScene(scene, accel, opt);
}

}  // namespace

nlohmann::json studyIntersectionShare(const Scene& scene, const std::vector<AccelKind>& kinds,
                                      int runs, const AccelOptions& options) {
  nlohmann::json j;
  std::printf("%-8s %12s %12s %12s %12s %10s\n", "backend", "render cpu s", "rays", "recorded",
              "replay cpu s", "share");
  for (AccelKind kind : kinds) {
    const std::unique_ptr<Accelerator> accel = makeAccelerator(kind, scene, options);
    // The first render sizes the recording and counts as the first timed run.
    RenderStats first;
    double render = oneThreadCpuSeconds([&] { first = renderOneThread(scene, *accel).stats; });
    const uint64_t rays = first.rays.total();
    // Every query when they fit in about 2M recorded rays; else one query in `stride` (picked
    // by RayRecorder's hash, so the render's mix of kinds is kept), scaled up below.
    constexpr uint64_t kMaxRecorded = 1 << 21;
    const uint64_t stride = std::max<uint64_t>(1, (rays + kMaxRecorded - 1) / kMaxRecorded);
    RayRecorder recorder(*accel, stride);
    renderOneThread(scene, recorder);
    const std::vector<RecordedRay> recorded = recorder.take();
    // Interleaved, so that a busy moment of a shared machine meets renders and replays alike.
    double replay = kInfinity;
    for (int run = 0; run < runs; ++run) {
      if (run > 0)
        render = std::min(render, oneThreadCpuSeconds([&] { renderOneThread(scene, *accel); }));
      replay = std::min(replay,
                        oneThreadCpuSeconds([&] { replaySeconds(*accel, recorded, 1, true, 1); }));
    }
    // With a stride, the recorded rays stand for all of the render's.
    const double scaled =
        stride == 1 || recorded.empty() ? replay : replay * double(rays) / double(recorded.size());
    const double share = render > 0 ? scaled / render : 0;
    const std::string name(accel->name());
    std::printf("%-8s %12.3f %12llu %12zu %12.3f %9.1f%%\n", name.c_str(), render,
                (unsigned long long)rays, recorded.size(), scaled, 100 * share);
    std::fflush(stdout);
    j["intersection_share"][name] = {{"render_seconds", render},
                                     {"rays", rays},
                                     {"recorded_rays", recorded.size()},
                                     {"replay_seconds", scaled},
                                     {"share", share}};
  }
  return j;
}

}  // namespace glint
