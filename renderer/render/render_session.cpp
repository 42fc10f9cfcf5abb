#include "render/render_session.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/check.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/word_list.h"

namespace glint {

namespace {

// What a frame holds per pixel at its peak (checkFrameFits), in parts named for the message:
// - its colour and sampling state: its RGBA in float, a float copy (to develop it for
//   display, or to clamp it for the file) and the display image's codes; its state between
//   passes, and the window's copy of it where a crop samples an apron; whether a pass takes
//   it; the adaptive choices (ChoiceCache);
// - its AOVs: each channel's sum, resolved value (double) and packed float; the object id's
//   and Cryptomatte's per-pixel tables;
// - the state written with a frame that can be continued: a copy of its film with the state's
//   channels;
// - previews: each a copy of the states and a resolved film, written with its state.
// The AOV planes' channels come from the layout itself, made on a one-pixel film.
struct FrameBytes {
  size_t total = 0;
  std::vector<std::string> parts;  // "AOVs 140", ...

  void add(const std::string& part, size_t bytes) {
    if (bytes == 0) return;
    total += bytes;
    parts.push_back(part + " " + std::to_string(bytes));
  }
};

FrameBytes frameBytesPerPixel(const Scene& scene, const RenderOptions& opt, const PassPlan& plan,
                              bool apron) {
  Film probe(1, 1, PixelWindow{0, 1, 0, 1});
  const AovLayout layout = AovLayout::create(opt.aovs, scene, probe);
  size_t aovChannels = 0;
  for (const FilmPlane& plane : probe.planes()) aovChannels += plane.channels.size();
  constexpr size_t kRgba = 4 * sizeof(float), kDisplayCodes = 4 * sizeof(uint16_t);
  FrameBytes bytes;
  bytes.add("colour and sampling state",
            2 * kRgba + kDisplayCodes + (apron ? 2 : 1) * sizeof(PixelEstimate) + sizeof(uint8_t) +
                (plan.adaptive() ? 5 * sizeof(double) + sizeof(int64_t) : 0));
  bytes.add("AOVs", aovChannels * (2 * sizeof(double) + sizeof(float)) +
                        (layout.objectId != SIZE_MAX ? sizeof(CoverageTable) : 0) +
                        (layout.cryptoObject != SIZE_MAX ? 2 * sizeof(CoverageTable) : 0));
  const size_t withState = resumeStateBytesPerPixel() + aovChannels * sizeof(double);
  const char* continuedBy = opt.resumeFrom                      ? "--resume"
                            : opt.sampling.progressive          ? "--resumable"
                            : opt.sampling.timeLimitSeconds > 0 ? "--time-limit"
                                                                : nullptr;
  if (continuedBy) bytes.add(std::string("the state kept for ") + continuedBy, withState);
  if (opt.previews && plan.ends.size() > 1)  // one pass: no preview
    bytes.add("previews", sizeof(PixelEstimate) + kRgba + aovChannels * sizeof(double) +
                              (continuedBy ? 0 : withState));
  return bytes;
}

// An adaptive frame continues as a straight render only if its passes are where this plan's
// are: the last it finished is one of the plan's ends, and the one it cut short the next. Their
// ends double from the first pass up to --max-spp: a frame finished at --max-spp 20 (8, 16, 20)
// has taken a pass that a render to 32 (8, 16, 32) never takes. Any position suits the other
// renders, whose passes choose every pixel below their end.
void checkResumablePosition(const PassPlan& plan, const PassPosition& at) {
  if (!plan.adaptive()) return;
  const auto next = std::upper_bound(plan.ends.begin(), plan.ends.end(), at.finishedEnd);
  const bool finishedOnPlan = at.finishedEnd == 0 || std::find(plan.ends.begin(), plan.ends.end(),
                                                               at.finishedEnd) != plan.ends.end();
  if (finishedOnPlan && (at.cutEnd == 0 || (next != plan.ends.end() && *next == at.cutEnd))) return;
  std::string ends;
  for (const int end : plan.ends) ends += (ends.empty() ? "" : ", ") + std::to_string(end);
  throw UsageError("--resume: the frame's adaptive passes stopped at " +
                   std::to_string(at.cutEnd > 0 ? at.cutEnd : at.finishedEnd) +
                   " spp, which this render's passes (" + ends +
                   ") do not reach on their way: a continued frame takes the choices a "
                   "straight render takes only where their passes end alike; give a --max-spp "
                   "whose passes, doubling from --min-spp, include it");
}

// Throws UsageError where the state a render left cannot be continued by this one.
void checkResumable(const PassPlan& plan, const RenderOptions& opt, const PixelWindow& window,
                    const PixelWindow& sampledWindow) {
  const ResumeState& from = *opt.resumeFrom;
  if (sampledWindow.area() != window.area())
    throw UsageError(
        "--resume continues an adaptive render of the full frame only: a crop's "
        "adaptive sampling depends on pixels around it, whose state is not kept");
  GLINT_CHECK(from.estimates.size() == size_t(sampledWindow.area()));
  if (opt.aovs.needsSamples())
    throw UsageError(
        "--resume continues the beauty and its variance only: the other AOVs' "
        "sums are not kept with the frame");
  checkResumablePosition(plan, from.position);
}

// What the progress line knows before the first pass.
ProgressPlan progressPlan(const PassPlan& plan, const PixelWindow& sampledWindow, bool resumed) {
  ProgressPlan p;
  p.totalWork = sampledWindow.area() * plan.maxSpp;
  p.workIsBound = plan.adaptive();
  if (plan.timeLimitSeconds > 0) p.timeLimitSeconds = plan.timeLimitSeconds;
  // A continued frame's first pass is behind it: the limit holds from its first pass taken.
  if (!resumed) p.firstPassWork = sampledWindow.area() * plan.ends.front();
  return p;
}

RenderOptions withoutAovs(RenderOptions opt) {
  opt.aovs = {};
  return opt;
}

// The options the session keeps: the state a frame continues from is copied by the constructor
// and may be gone after it.
RenderOptions withoutResumeState(RenderOptions opt) {
  opt.resumeFrom = nullptr;
  return opt;
}

// The pixels' states inside `window` (of the sampled window), row-major.
PixelEstimates estimatesIn(const FrameContext& f, const PixelWindow& window) {
  PixelEstimates out;
  out.reserve(static_cast<size_t>(window.area()));
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x) out.push_back(f.estimate(x, y));
  return out;
}

// The part of a per-pixel mask over `from` that lies in `window` (inside it), row-major.
std::vector<uint8_t> windowPart(const std::vector<uint8_t>& mask, const PixelWindow& from,
                                const PixelWindow& window) {
  std::vector<uint8_t> out;
  out.reserve(static_cast<size_t>(window.area()));
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x)
      out.push_back(mask[size_t(y - from.y0) * size_t(from.width()) + size_t(x - from.x0)]);
  return out;
}

// The frame as it stands in `window`: each pixel's mean and the AOVs' finished values.
Film resolveFrame(const FrameContext& f, const PixelWindow& window) {
  const Film& sums = f.aovSums;
  Film out(sums.fullWidth(), sums.fullHeight(), window, FilmPixels::Unwritten);
  for (const FilmPlane& plane : sums.planes())
    out.addPlane(plane.name, plane.channels, plane.isUint);
  for (const auto& [key, value] : sums.stringAttributes()) out.addAttribute(key, value);
  for (const auto& [key, value] : sums.intAttributes()) out.addAttribute(key, value);
  // On the render's threads: each pixel is written from its own state alone, every one of
  // the window's (the film's first writes).
  forEachRow(window.y0, window.y1, [&](int y) {
    for (int x = window.x0; x < window.x1; ++x) {
      const PixelEstimate& pixel = f.estimate(x, y);
      double rgba[4];
      pixel.mean(rgba);
      out.setPixel(x, y, rgba[0], rgba[1], rgba[2], rgba[3]);
      if (f.opt.aovs.any()) resolveAovs(f.aovLayout, sums, f.aovTables, pixel, out, x, y);
    }
  });
  return out;
}

// The statistics of the frame as it stands, besides the rays and time; returns the samples its
// pixels hold.
int64_t describeSamples(std::span<const PixelEstimate> estimates, SamplerKind sampler,
                        RenderStats& stats) {
  const FrameSummary summary = summariseFrame(estimates, sampler);
  stats.sampler = sampler;
  stats.estimated = summary.error;
  stats.minPixelSpp = static_cast<int>(summary.fewestSamples);
  stats.maxPixelSpp = static_cast<int>(summary.mostSamples);
  return summary.samples;
}

}  // namespace

RenderSession::Shape RenderSession::planFrame(const Scene& scene, const RenderOptions& opt) {
  const RenderSettings& rs = scene.render;
  Shape s{PassPlan::make(rs.spp, rs.sampler, opt.sampling), {}, {}};
  checkSampleSets(scene, s.plan.maxSpp);
  s.window = opt.crop.value_or(PixelWindow{0, rs.width, 0, rs.height});
  // Adaptive sampling decides from each pixel's neighbours: a crop samples an apron around it
  // too, so that its pixels are sampled as in the full frame (PassPlan::apron).
  const int apron = s.plan.apron();
  s.sampledWindow = {std::max(0, s.window.x0 - apron), std::min(rs.width, s.window.x1 + apron),
                     std::max(0, s.window.y0 - apron), std::min(rs.height, s.window.y1 + apron)};
  const FrameBytes bytes =
      frameBytesPerPixel(scene, opt, s.plan, s.sampledWindow.area() != s.window.area());
  checkFrameFits(s.sampledWindow.area(), bytes.total, availableMemoryBytes(),
                 wordList(bytes.parts));
  // AOV work happens only when AOVs are asked for (leave out what is not needed).
  if (opt.integrator == IntegratorKind::Reference && opt.aovs.any())
    throw UsageError("the reference integrator renders the beauty only: drop --aov");
  if (opt.resumeFrom) checkResumable(s.plan, opt, s.window, s.sampledWindow);
  return s;
}

RenderSession::RenderSession(const Scene& scene, const Accelerator& accel, const RenderOptions& opt)
    : scene_(scene),
      accel_(accel),
      opt_(withoutResumeState(opt)),
      probeOptions_(withoutAovs(opt_)),
      start_(Clock::now()),
      boundedStop_(opt.cancel == &interrupt::requested() ? std::make_optional<interrupt::Sampling>()
                                                         : std::nullopt),
      shape_(planFrame(scene, opt)),
      threads_(threadCount(opt.threads)),
      tileSize_(effectiveTileSize(shape_.sampledWindow, opt.tileSize, threads_)),
      arena_(threads_),
      tiles_(makeTiles(shape_.sampledWindow, tileSize_, opt.tileOrder)),
      camera_(scene.cameraDesc, scene.render.width, scene.render.height),
      cameraSampling_(scene, camera_),
      sampler_(plan_.sampler, plan_.maxSpp, scene.render.seed),
      // Only its AOV planes are read: its RGBA stays unwritten, and untouched.
      aovSums_(scene.render.width, scene.render.height, shape_.sampledWindow,
               FilmPixels::Unwritten),
      aovLayout_(AovLayout::create(opt.aovs, scene, aovSums_)),
      aovTables_(aovLayout_, shape_.sampledWindow),
      integrator_(makeTilePasses(opt.integrator, scene, accel, plan_.footprintSpp())),
      progress_(progressPlan(plan_, shape_.sampledWindow, opt.resumeFrom != nullptr), opt.progress,
                start_),
      estimates_(size_t(shape_.sampledWindow.area())),
      sampled_(estimates_.size(), 1),
      tileCounters_(tiles_.size()),
      frame_{scene_,          accel_,   opt_,       camera_,
             cameraSampling_, sampler_, aovLayout_, loggedNonfinite_,
             estimates_,      aovSums_, aovTables_, PixelSlots::all(shape_.sampledWindow)} {
  // Where the passes stand, from where the continued frame's stood: its pixels may hold more
  // than the ends this plan skips (--spp 24, continued to 64: 24 against 16), and a stop
  // before its cut pass is taken again must keep that pass's choice.
  if (opt.resumeFrom) {
    resumedAt_ = opt.resumeFrom->position;
    position_ = *resumedAt_;
  }
  // The pixels' states are first written on the render's threads, block by block, so that the
  // first pass does not wait for one thread to zero them.
  timing_.threads = threads_;
  timing_.width = shape_.sampledWindow.width();
  timing_.height = shape_.sampledWindow.height();
  timing_.tileSize = tileSize_;
  const Clock::time_point initStart = Clock::now();
  timing_.setupSeconds = std::chrono::duration<double>(initStart - start_).count();
  arena_.run([&] {
    const std::span<PixelEstimate> states(estimates_);
    if (opt.resumeFrom) {
      const PixelEstimates& from = opt.resumeFrom->estimates;
      forEachBlock(states.size(), [&](size_t begin, size_t end) {
        std::copy(from.begin() + ptrdiff_t(begin), from.begin() + ptrdiff_t(end),
                  states.begin() + ptrdiff_t(begin));
      });
    } else {
      fillInBlocks(states, PixelEstimate{});
    }
  });
  phaseEnd_ = Clock::now();
  timing_.initSeconds = std::chrono::duration<double>(phaseEnd_ - initStart).count();
}

RenderSession::~RenderSession() = default;

bool RenderSession::measureSpread() {
  GLINT_CHECK(!finished_);
  bool measured = false;
  arena_.run([&] { measured = measureSpreadOnThreads(); });
  return measured;
}

bool RenderSession::runPass() {
  GLINT_CHECK(!finished_);
  bool finished = false;
  arena_.run([&] { finished = takeNextPass(); });
  return finished;
}

void RenderSession::runToEnd(const PassCallback& onPass) {
  GLINT_CHECK(!finished_);
  // From here on, on the render's threads: the tiles, and the per-pixel work between passes
  // (choosing pixels, the statistics, the resolved frame), which other threads would wait for.
  arena_.run([&] {
    while (takeNextPass())
      if (onPass && passesLeft()) onPass(snapshot());
  });
}

RenderResult RenderSession::snapshot() const {
  GLINT_CHECK(!finished_);
  std::optional<Film> film;
  arena_.run([&] { film.emplace(resolveFrame(frame_, shape_.window)); });
  const bool apron = shape_.sampledWindow.area() != shape_.window.area();
  return {std::move(*film),
          stats_,
          partial_,
          tileSize_,
          apron ? estimatesIn(frame_, shape_.window) : estimates_,
          position_};
}

RenderResult RenderSession::finish() {
  GLINT_CHECK(!finished_);
  finished_ = true;
  // A frame whose driver stopped taking passes is short of its plan, as one a cancel stopped
  // between two passes is.
  const bool partial = partial_ || (!ended_ && next_ < plan_.ends.size());
  std::optional<Film> film;
  arena_.run([&] {
    progress_.finish(stats_.timeLimitReached ? "the time limit" : partial ? "an interrupt" : "");
    timedLoops([&] { film.emplace(resolveFrame(frame_, shape_.window)); });
    refreshStats();
    timing_.finishLoopSeconds = loopSeconds_;
    timing_.finishSeconds =
        std::chrono::duration<double>(Clock::now() - phaseEnd_).count() - loopSeconds_;
    stats_.timing = timing_;
  });
  boundedStop_.reset();
  RenderResult result{std::move(*film),    std::move(stats_), partial, tileSize_, {},
                      std::move(position_)};
  // Moved, not copied: the frame's states, or the window's that refreshStats took from them.
  result.estimates = shape_.sampledWindow.area() == shape_.window.area()
                         ? std::move(estimates_)
                         : std::move(cropEstimates_);
  return result;
}

bool RenderSession::takeNextPass() {
  for (; passesLeft(); ++next_) {
    const int end = plan_.ends[next_];
    // A continued frame's finished passes are not taken again: their choices would read a
    // state later passes have moved on (a straight render takes each from the one before).
    if (resumedAt_ && end <= resumedAt_->finishedEnd) continue;
    // From the second pass on, adaptive choices weigh each pixel by the frame's spread.
    if (plan_.adaptive() && next_ > 0 && !measureSpreadOnThreads()) return false;
    const int64_t pixels = choosePixels(end);
    if (pixels == 0) {  // every pixel is past this pass (continued), or met its target
      passFinished(end);
      continue;
    }
    if (!renderChosen(pixels)) return false;
    passFinished(end);
    const int64_t samples = refreshStats();
    stats_.passes.push_back({end, double(samples) / double(shape_.window.area()), stats_.seconds,
                             stats_.estimated, pixels});
    ++next_;
    return true;
  }
  return false;
}

// The probes' first pass, rendered on their own (beauty only) so that a crop or a continued
// frame measures the frame's spread as the full frame does.
bool RenderSession::measureSpreadOnThreads() {
  if (!plan_.adaptive() || spread_) return true;
  if (ended_) return false;
  const RenderSettings& rs = scene_.render;
  const ProbeLattice lattice = ProbeLattice::of(rs.width, rs.height);
  std::vector<PixelEstimate> probes(size_t(lattice.columns) * size_t(lattice.rows));
  const FrameContext probeFrame{
      scene_,          accel_,   probeOptions_, camera_,
      cameraSampling_, sampler_, aovLayout_,    loggedNonfinite_,
      probes,          aovSums_, aovTables_,    PixelSlots::probes(lattice, rs.width, rs.height)};
  const std::vector<uint8_t> all(probes.size(), 1);
  std::atomic<bool> never{false};
  const PassContext pass{plan_.minSpp, all, std::nullopt, never};
  Progress silent({}, false);
  const std::vector<PixelWindow> frameTiles =
      makeTiles(PixelWindow{0, rs.width, 0, rs.height}, tileSize_, opt_.tileOrder);
  probeCounters_.assign(frameTiles.size(), {});
  if (renderTiles(probeFrame, pass, frameTiles, probeCounters_, silent, 0)) {
    partial_ = ended_ = true;
    refreshStats();
    return false;
  }
  spread_ = FrameSpread::of(probes);
  return true;
}

// Marks in sampled_ the pixels the pass to `end` takes, and returns how many.
int64_t RenderSession::choosePixels(int end) {
  // The pass a stop cut short goes on with the pixels it had chosen.
  if (resumedAt_ && end == resumedAt_->cutEnd) {
    sampled_ = resumedAt_->cutChosen;
    return std::count(sampled_.begin(), sampled_.end(), uint8_t{1});
  }
  int64_t chosen = 0;
  timedLoops([&] {
    chosen = plan_.choosePixels(estimates_, shape_.sampledWindow.width(), end,
                                spread_.value_or(FrameSpread{}), choiceCache_, sampled_);
  });
  return chosen;
}

// Renders the next pass on the pixels chosen; returns false when a stop cut it short.
bool RenderSession::renderChosen(int64_t pixels) {
  const size_t k = next_;
  if (plan_.adaptive()) progress_.replan(pixels * (plan_.maxSpp - (k > 0 ? plan_.ends[k - 1] : 0)));
  // The time limit applies from the second pass on: the first is what makes a frame.
  std::optional<Clock::time_point> deadline;
  if (plan_.timeLimitSeconds > 0 && k > 0)  // a limit past 30 years is none (no overflow)
    deadline = start_ + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(std::min(plan_.timeLimitSeconds, 1e9)));
  const PassContext pass{plan_.ends[k], sampled_, deadline, deadlinePassed_};
  if (!renderTiles(frame_, pass, tiles_, tileCounters_, progress_, plan_.ends[k])) return true;
  passCut(plan_.ends[k]);
  return false;
}

bool RenderSession::renderTiles(const FrameContext& frame, const PassContext& pass,
                                const std::vector<PixelWindow>& tiles,
                                std::vector<RayCounters>& counters, Progress& progress, int spp) {
  PassTiming& timing = timing_.passes.emplace_back();
  timing.spp = spp;
  // A tile's expected cost: its pixels that take part, each costing the rays a sample of the
  // tile has traced so far (its counters: no pixel state is read, a loop bound by memory).
  std::vector<double> costs(tiles.size(), 0.0);
  timedLoops([&] {
    tbb::parallel_for(size_t{0}, tiles.size(), [&](size_t i) {
      const PixelWindow& tile = tiles[i];
      int64_t taking = 0;
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x)
          taking += frame.slots.holds(x, y) && pass.sampled[frame.slots.slot(x, y)];
      const RayCounters& c = counters[i];
      const double raysPerSample = c.camera > 0 ? double(c.total()) / double(c.camera) : 1.0;
      costs[i] = double(taking) * raysPerSample;
    });
  });
  const std::vector<uint32_t> order = orderByCost(costs);
  const Clock::time_point begin = Clock::now();
  timing.loopSeconds = loopSeconds_;
  timing.serialSeconds = std::chrono::duration<double>(begin - phaseEnd_).count() - loopSeconds_;
  loopSeconds_ = 0;
  std::atomic<bool> stopped{false};
  TileWork work{tiles,   counters, progress,
                stopped, threads_, {order, &timing.tiles, opt_.tileCpuTimes}};
  summaryFresh_ = false;
  // A pass with no work leaves every tile as it is: an empty order would mean every tile.
  if (!order.empty()) integrator_->render(frame, pass, work);
  phaseEnd_ = Clock::now();
  timing.tilesSeconds = std::chrono::duration<double>(phaseEnd_ - begin).count();
  return stopped;
}

// A stop cut the pass to `end` short: the frame ends there, keeping the pass's choice so that a
// continuation takes it again.
void RenderSession::passCut(int end) {
  stats_.timeLimitReached = deadlinePassed_.load();
  partial_ = !stats_.timeLimitReached;
  ended_ = true;
  position_.cutEnd = end;
  position_.cutChosen = windowPart(sampled_, shape_.sampledWindow, shape_.window);
  refreshStats();
}

void RenderSession::passFinished(int end) {
  position_.finishedEnd = end;
  if (position_.cutEnd <= end) position_.cutEnd = 0, position_.cutChosen.clear();
}

int64_t RenderSession::refreshStats() {
  stats_.rays = {};
  for (const RayCounters& c : tileCounters_) stats_.rays += c;
  for (const RayCounters& c : probeCounters_) stats_.rays += c;
  stats_.integrator = opt_.integrator;
  stats_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  stats_.timing = timing_;
  // The pixels are read again only where a phase has changed them since (finish() after the
  // last pass's statistics would read the whole frame for nothing).
  if (!summaryFresh_)
    timedLoops(
        [&] { summarySamples_ = describeSamples(windowEstimates(), plan_.sampler, stats_); });
  summaryFresh_ = true;
  return summarySamples_;
}

// The pixels' states in the window: the frame's own where it samples no apron, else a copy.
const PixelEstimates& RenderSession::windowEstimates() {
  if (shape_.sampledWindow.area() == shape_.window.area()) return estimates_;
  cropEstimates_ = estimatesIn(frame_, shape_.window);
  return cropEstimates_;
}

}  // namespace glint
