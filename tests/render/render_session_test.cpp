// A render session driven on its own, pass by pass, as `glint render`, previews and interrupts
// drive it: every pass depends only on the state the passes before it left, so a frame taken a
// pass at a time, snapshotted between passes, cut inside one, or continued from a snapshot
// holds the bytes a straight render's passes give.
#include "render/render_session.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "accel/accelerator.h"
#include "io/scene_loader.h"
#include "render/render_job.h"

namespace glint {
namespace {

// soft_shadows at a small size: two area lights' penumbrae, so pixels differ in their noise
// and adaptive sampling has something to choose.
Scene softShadows(int spp, SamplerKind sampler) {
  Scene scene = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/soft_shadows.json");
  scene.render.width = 48;
  scene.render.height = 32;
  scene.render.spp = spp;
  scene.render.seed = 5;
  scene.render.sampler = sampler;
  return scene;
}

RenderOptions quiet(int threads = 2) {
  RenderOptions opt;
  opt.progress = false;
  opt.threads = threads;
  return opt;
}

// A plain render in passes from 2 (at 16 spp: 2, 4, 8, 16), more passes than its default's from
// 8, for the tests of what happens between passes.
RenderOptions passesFromTwo(int threads = 2) {
  RenderOptions opt = quiet(threads);
  opt.sampling.minSpp = 2;
  return opt;
}

RenderOptions adaptive() {
  RenderOptions opt = quiet();
  opt.sampling.target.rmse = 0.004;  // reached by some pixels before --max-spp, not by all
  opt.sampling.minSpp = 4;
  opt.sampling.maxSpp = 64;
  return opt;
}

// Every channel of every pixel, in the film's doubles.
std::vector<double> pixelsOf(const Film& film) {
  std::vector<double> v;
  const PixelWindow& w = film.window();
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x)
      for (int c = 0; c < 4; ++c) v.push_back(film.pixel(x, y)[c]);
  return v;
}

// Whether two pixels' states are the same bits (means, coverage, rays, counts); field by field,
// since the padding between them is not part of the state.
bool sameBits(const PixelEstimate& a, const PixelEstimate& b) {
  for (int h = 0; h < 2; ++h) {
    const HalfEstimate &x = a.half[h], &y = b.half[h];
    if (std::memcmp(x.mean, y.mean, sizeof x.mean) != 0 ||
        std::memcmp(&x.alpha, &y.alpha, sizeof x.alpha) != 0 || x.rays != y.rays ||
        x.count != y.count)
      return false;
  }
  return true;
}

bool sameBits(std::span<const PixelEstimate> a, std::span<const PixelEstimate> b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!sameBits(a[i], b[i])) return false;
  return true;
}

std::vector<int> passEnds(const RenderStats& stats) {
  std::vector<int> ends;
  for (const PassRecord& p : stats.passes) ends.push_back(p.spp);
  return ends;
}

TEST(RenderSession, PassByPassGivesTheFrameRenderSceneGives) {
  // A plain frame (passes to 2, 4, 8, 16) and an adaptive one (4, 8, 16, 32, 64), the latter
  // with its spread measured before the first pass rather than when the second needs it: the
  // probes are their own pixels, so when they are rendered does not matter.
  struct Case {
    const char* name;
    RenderOptions opt;
    bool spreadFirst;
  };
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  for (const Case& c :
       {Case{"plain", passesFromTwo(), false}, Case{"adaptive", adaptive(), true}}) {
    const RenderResult straight = renderScene(scene, *accel, c.opt);
    RenderSession session(scene, *accel, c.opt);
    if (c.spreadFirst) {
      EXPECT_TRUE(session.measureSpread());
    }
    int passes = 0;
    while (session.runPass()) ++passes;
    EXPECT_FALSE(session.passesLeft());
    const RenderResult stepped = session.finish();
    EXPECT_FALSE(stepped.partial) << c.name;
    EXPECT_EQ(passes, int(straight.stats.passes.size())) << c.name;
    EXPECT_EQ(passEnds(stepped.stats), passEnds(straight.stats)) << c.name;
    EXPECT_EQ(pixelsOf(stepped.film), pixelsOf(straight.film)) << c.name;
    EXPECT_TRUE(sameBits(stepped.estimates, straight.estimates)) << c.name;
    EXPECT_EQ(stepped.position, straight.position) << c.name;
    EXPECT_EQ(stepped.stats.rays.total(), straight.stats.rays.total()) << c.name;
    // The plain frame takes every pass of its plan; the adaptive one stops pixels early.
    if (c.spreadFirst) {
      EXPECT_LT(stepped.stats.minPixelSpp, stepped.stats.maxPixelSpp);
    } else {
      EXPECT_EQ(passEnds(stepped.stats), (std::vector<int>{2, 4, 8, 16}));
    }
  }
}

TEST(RenderSession, APlainFrameIsTheSameBitsWhateverItsPasses) {
  // A pixel's samples are added in index order whatever the passes, so a plain frame taken in
  // one pass (--min-spp equal to the spp) or in passes from 2 or 4 is the frame of the default
  // passes from 8: the same pixels, states, rays and final error estimate; only the passes'
  // records differ.
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const RenderResult byDefault = renderScene(scene, *accel, quiet());
  ASSERT_EQ(passEnds(byDefault.stats), (std::vector<int>{8, 16}));
  for (const auto& [first, ends] : std::vector<std::pair<int, std::vector<int>>>{
           {16, {16}}, {2, {2, 4, 8, 16}}, {4, {4, 8, 16}}}) {
    RenderOptions opt = quiet();
    opt.sampling.minSpp = first;
    const RenderResult r = renderScene(scene, *accel, opt);
    EXPECT_EQ(passEnds(r.stats), ends) << first;
    EXPECT_EQ(pixelsOf(r.film), pixelsOf(byDefault.film)) << first;
    EXPECT_TRUE(sameBits(r.estimates, byDefault.estimates)) << first;
    EXPECT_EQ(r.stats.rays.total(), byDefault.stats.rays.total()) << first;
    EXPECT_EQ(r.stats.estimated.rmse, byDefault.stats.estimated.rmse) << first;
    EXPECT_EQ(r.stats.estimated.relmse, byDefault.stats.estimated.relmse) << first;
    EXPECT_EQ(r.stats.passes.back().estimated.rmse, byDefault.stats.passes.back().estimated.rmse)
        << first;
  }
}

TEST(RenderSession, ASnapshotHoldsExactlyThePassesFinished) {
  // Sobol's sets are the same whatever the total, so the frame after the pass to 4 of a 16-spp
  // render is the frame a 4-spp render makes.
  const Scene at16 = softShadows(16, SamplerKind::Sobol);
  const Scene at4 = softShadows(4, SamplerKind::Sobol);
  const auto accel = makeAccelerator(AccelKind::Embree, at16);
  RenderSession session(at16, *accel, passesFromTwo());
  ASSERT_TRUE(session.runPass());  // to 2
  ASSERT_TRUE(session.runPass());  // to 4
  const RenderResult snap = session.snapshot();
  EXPECT_FALSE(snap.partial);
  EXPECT_EQ(passEnds(snap.stats), (std::vector<int>{2, 4}));
  // Every pixel took both passes: 4 samples each, 48 × 32 of them.
  EXPECT_EQ(snap.stats.minPixelSpp, 4);
  EXPECT_EQ(snap.stats.maxPixelSpp, 4);
  EXPECT_DOUBLE_EQ(snap.stats.passes.back().meanSpp, 4.0);
  EXPECT_EQ(snap.stats.passes.back().pixelsSampled, 48 * 32);
  EXPECT_EQ(snap.position, (PassPosition{4, 0, {}}));
  ASSERT_EQ(snap.estimates.size(), size_t{48 * 32});
  for (const PixelEstimate& p : snap.estimates) ASSERT_EQ(p.samples(), 4);
  const RenderResult at4Frame = renderScene(at4, *accel, quiet());
  EXPECT_EQ(pixelsOf(snap.film), pixelsOf(at4Frame.film));
  EXPECT_TRUE(sameBits(snap.estimates, at4Frame.estimates));
  // Taking a snapshot changes nothing the later passes see.
  EXPECT_TRUE(session.passesLeft());
  session.runToEnd();
  const RenderResult finished = session.finish();
  EXPECT_EQ(pixelsOf(finished.film), pixelsOf(renderScene(at16, *accel, quiet()).film));
}

TEST(RenderSession, AFrameContinuedFromASnapshotEndsAsAStraightRender) {
  // The stratified sampler (laid out for the spp, continued to the same spp) and adaptive
  // sampling, whose later choices read the state the snapshot's passes left.
  struct Case {
    const char* name;
    RenderOptions opt;
    int passesBefore;
    int nextEnd;  // the end of the first pass the continuation takes
  };
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  for (const Case& c :
       {Case{"plain", passesFromTwo(), 2, 8}, Case{"adaptive", adaptive(), 3, 32}}) {
    const RenderResult straight = renderScene(scene, *accel, c.opt);
    RenderSession first(scene, *accel, c.opt);
    for (int k = 0; k < c.passesBefore; ++k) ASSERT_TRUE(first.runPass()) << c.name;
    const RenderResult snap = first.snapshot();
    const ResumeState left{snap.estimates, snap.position};
    RenderOptions opt = c.opt;
    opt.resumeFrom = &left;
    opt.threads = 3;  // another thread count: the bytes do not depend on it
    RenderSession continued(scene, *accel, opt);
    ASSERT_TRUE(continued.runPass()) << c.name;
    EXPECT_EQ(passEnds(continued.snapshot().stats), (std::vector<int>{c.nextEnd})) << c.name;
    continued.runToEnd();
    const RenderResult end = continued.finish();
    EXPECT_FALSE(end.partial) << c.name;
    EXPECT_EQ(pixelsOf(end.film), pixelsOf(straight.film)) << c.name;
    EXPECT_TRUE(sameBits(end.estimates, straight.estimates)) << c.name;
  }
}

TEST(RenderSession, ACancelKeepsEachPixelAtTheEndOfAPass) {
  // Passes to 2, 4, 8, 16 on one thread (so where the cancel lands is fixed): cancelled after
  // 3 of the pass to 8's 4 new samples a pixel, counted over the frame.
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const int64_t pixels = 48 * 32;
  std::atomic<bool> cancel{false};
  int64_t samplesOfPass8 = -1;  // counting from the pass to 8 on
  RenderOptions opt = passesFromTwo(1);
  opt.cancel = &cancel;
  opt.sampleHook = [&](int, int, Radiance&) {
    if (samplesOfPass8 >= 0 && ++samplesOfPass8 == pixels * 3) cancel = true;
  };
  RenderSession session(scene, *accel, opt);
  ASSERT_TRUE(session.runPass());
  ASSERT_TRUE(session.runPass());
  const RenderResult at4 = session.snapshot();
  samplesOfPass8 = 0;
  EXPECT_FALSE(session.runPass());  // cut
  EXPECT_FALSE(session.passesLeft());
  const RenderResult partial = session.finish();
  EXPECT_TRUE(partial.partial);
  EXPECT_FALSE(partial.stats.timeLimitReached);
  EXPECT_EQ(passEnds(partial.stats), (std::vector<int>{2, 4}));
  EXPECT_EQ(partial.position.finishedEnd, 4);
  EXPECT_EQ(partial.position.cutEnd, 8);
  // The frame at 8 spp, uncut, for the pixels the cut pass finished.
  RenderSession uncut(scene, *accel, passesFromTwo(1));
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(uncut.runPass());
  const RenderResult at8 = uncut.snapshot();
  // Each pixel holds 4 samples (the pass to 8 had not finished it) or 8; then it is exactly
  // the frame after that pass.
  int64_t atFour = 0, atEight = 0;
  for (size_t i = 0; i < partial.estimates.size(); ++i) {
    const int64_t n = partial.estimates[i].samples();
    ASSERT_TRUE(n == 4 || n == 8) << i << ": " << n;
    ++(n == 4 ? atFour : atEight);
    EXPECT_TRUE(sameBits(partial.estimates[i], (n == 4 ? at4 : at8).estimates[i])) << i;
  }
  // Three quarters of the pass's samples were in: a pixel's state is kept once its four are,
  // so about three quarters of the pixels (all but the chunk in flight) hold 8.
  EXPECT_GT(atFour, 0);
  EXPECT_GT(atEight, 0);
  EXPECT_NEAR(double(atEight) / double(pixels), 0.75, 0.05);

  // A cancel between two passes leaves the frame at the last pass finished, bit for bit.
  std::atomic<bool> stopNow{false};
  RenderOptions between = passesFromTwo();
  between.cancel = &stopNow;
  RenderSession two(scene, *accel, between);
  ASSERT_TRUE(two.runPass());
  ASSERT_TRUE(two.runPass());
  const RenderResult before = two.snapshot();
  stopNow = true;
  EXPECT_FALSE(two.runPass());
  const RenderResult stopped = two.finish();
  EXPECT_TRUE(stopped.partial);
  EXPECT_EQ(pixelsOf(stopped.film), pixelsOf(before.film));
  EXPECT_EQ(stopped.position.finishedEnd, 4);
  EXPECT_EQ(stopped.position.cutEnd, 8);
}

TEST(RenderSession, FinishingWithPassesLeftGivesAPartialFrame) {
  // A driver that stops taking passes (between the pass to 4 and the pass to 8) has a frame
  // short of its plan: partial, at its last pass, and continued it ends as a straight one.
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderSession session(scene, *accel, passesFromTwo());
  ASSERT_TRUE(session.runPass());
  ASSERT_TRUE(session.runPass());
  const RenderResult early = session.finish();
  EXPECT_TRUE(early.partial);
  EXPECT_EQ(early.stats.maxPixelSpp, 4);
  EXPECT_EQ(early.position, (PassPosition{4, 0, {}}));
  const ResumeState left{early.estimates, early.position};
  const std::vector<double> straight = pixelsOf(renderScene(scene, *accel, quiet()).film);
  // Continued with the same passes, or with the default's from 8, whose plan never ends at 4:
  // the pass to 8 takes the pixels on from the 4 they hold.
  for (const RenderOptions& plan : {passesFromTwo(), quiet()}) {
    RenderOptions opt = plan;
    opt.resumeFrom = &left;
    EXPECT_EQ(pixelsOf(renderScene(scene, *accel, opt).film), straight) << plan.sampling.minSpp;
  }
}

TEST(RenderSession, AnAdaptiveFrameIsTheSameBitsForAnyThreadCountAndTileSize) {
  // Tiles are taken costliest first (by the rays their pixels' samples traced so far) and the
  // frame's states are first written on the render's threads: neither may change a bit. 1, 2
  // and 7 threads, tiles of 8 and 16 (7 threads and 8: tiles left over at every pass's end).
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions base = adaptive();
  base.threads = 1;
  const RenderResult one = renderScene(scene, *accel, base);
  ASSERT_LT(one.stats.minPixelSpp, one.stats.maxPixelSpp);  // the later passes are short
  for (const int threads : {2, 7})
    for (const int tileSize : {8, 16}) {
      RenderOptions opt = adaptive();
      opt.threads = threads;
      opt.tileSize = tileSize;
      const RenderResult r = renderScene(scene, *accel, opt);
      EXPECT_EQ(pixelsOf(r.film), pixelsOf(one.film)) << threads << " threads, " << tileSize;
      EXPECT_TRUE(sameBits(r.estimates, one.estimates)) << threads << " threads, " << tileSize;
      EXPECT_EQ(passEnds(r.stats), passEnds(one.stats)) << threads << " threads, " << tileSize;
      EXPECT_EQ(r.stats.rays.total(), one.stats.rays.total()) << threads << ", " << tileSize;
    }
}

TEST(RenderSession, BeforeItsFirstPassAFramesStatesAreZeroOnAnyThreads) {
  // The states are first written in blocks on the render's threads: a snapshot before any
  // pass holds what zeroed states hold (no samples, black and transparent) for 1 and 7 threads.
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const std::vector<PixelEstimate> zero(48 * 32);
  for (const int threads : {1, 7}) {
    RenderSession session(scene, *accel, quiet(threads));
    const RenderResult snap = session.snapshot();
    EXPECT_TRUE(sameBits(snap.estimates, zero)) << threads << " threads";
    EXPECT_EQ(pixelsOf(snap.film), std::vector<double>(48 * 32 * 4, 0.0)) << threads;
  }
}

TEST(RenderSession, TheScheduleNotesEachPhasesTilesWithWorkOnce) {
  // An adaptive frame's phases: each pass, and the probes (spp 0) that measure the spread
  // before the second. The first pass samples every pixel, so it takes every tile; later
  // passes only tiles with a pixel chosen; no phase takes a tile twice.
  const Scene scene = softShadows(16, SamplerKind::Stratified);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt = adaptive();
  opt.tileSize = 8;  // 6 x 4 = 24 tiles of the 48 x 32 frame
  const RenderResult r = renderScene(scene, *accel, opt);
  const RenderTiming& t = r.stats.timing;
  EXPECT_EQ(t.threads, 2);
  ASSERT_EQ(t.passes.size(), r.stats.passes.size() + 1);
  std::vector<int> ends;
  for (size_t i = 0; i < t.passes.size(); ++i) {
    std::set<uint32_t> taken;
    for (const TileTime& tile : t.passes[i].tiles) {
      EXPECT_LT(tile.tile, 24u) << i;
      EXPECT_TRUE(taken.insert(tile.tile).second) << "phase " << i << " tile " << tile.tile;
    }
    if (i != 1) ends.push_back(t.passes[i].spp);
  }
  EXPECT_EQ(t.passes[1].spp, 0);  // the probes
  EXPECT_EQ(ends, passEnds(r.stats));
  EXPECT_EQ(t.passes[0].tiles.size(), 24u);
  EXPECT_LT(t.passes.back().tiles.size(), 24u);  // the last pass's pixels are a few regions
}

}  // namespace
}  // namespace glint
