#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "app/accel_options.h"
#include "app/commands.h"
#include "app/farm_plan.h"
#include "app/frame_output.h"
#include "app/option_arity.h"
#include "app/render_output.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/sampler.h"
#include "film/atomic_file.h"
#include "film/display.h"
#include "film/exr_output.h"
#include "io/scene_loader.h"
#include "render/frame_record.h"
#include "render/pass_plan.h"
#include "render/render_job.h"
#include "render/render_session.h"

namespace glint {

namespace {

struct RenderArgs {
  std::string scenePath;
  std::string camera;                // a glTF file's camera, by name
  std::string environment;           // an image lighting a mesh file (--environment)
  std::vector<std::string> outputs;  // one, or one per --crop when several are given
  std::string display;
  DisplaySettings ocio;
  std::string accel = "embree";
  AccelOptions accelOptions;  // --rayclass-n-min, --rayclass-w-min
  std::string integrator = "production";
  std::string sampler;
  std::string statsJson;
  std::optional<int> spp, width, height, maxDepth, threads;
  std::optional<uint64_t> seed;
  std::optional<int> frame;
  std::string frames;
  std::vector<int> crop;  // 4 numbers per --crop
  int tileSize = 32;
  std::string tileOrder = "morton";
  bool half = false;
  bool multipart = false;
  bool transparentBackground = false;
  std::string aovs;
  std::string compression = "zip";
  bool compressionGiven = false;
  bool stats = false;
  bool quiet = false;
  SamplingRequest sampling;  // --target-rmse, --target-relmse, --time-limit, --min/max-spp
  double previewEvery = 0;   // seconds; 0: no previews
  std::string resume;        // a frame to continue
};

void applyOverrides(const RenderArgs& a, Scene& scene) {
  RenderSettings& r = scene.render;
  if (a.spp) r.spp = *a.spp;
  if (a.width) r.width = *a.width;
  if (a.height) r.height = *a.height;
  if (a.maxDepth) r.maxDepth = *a.maxDepth;
  if (a.seed) r.seed = *a.seed;
  if (!a.sampler.empty()) parseSamplerKind(a.sampler, r.sampler);
  if (a.transparentBackground) r.transparentBackground = true;
}

// The K-th --crop, checked against the frame; none when no --crop was given.
std::optional<PixelWindow> cropWindow(const RenderArgs& a, const RenderSettings& r, size_t k) {
  if (a.crop.empty()) return std::nullopt;
  const PixelWindow w{a.crop[4 * k], a.crop[4 * k + 1], a.crop[4 * k + 2], a.crop[4 * k + 3]};
  if (w.x0 < 0 || w.x1 > r.width || w.x0 >= w.x1 || w.y0 < 0 || w.y1 > r.height || w.y0 >= w.y1)
    throw SceneError({"--crop", 0}, "",
                     "crop [" + std::to_string(w.x0) + "," + std::to_string(w.x1) + ") x [" +
                         std::to_string(w.y0) + "," + std::to_string(w.y1) +
                         ") must be non-empty and inside the " + std::to_string(r.width) + "x" +
                         std::to_string(r.height) + " frame");
  return w;
}

void printStats(const Scene& scene, const RenderStats& st) {
  const auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("(none)") : s;
  };
  std::printf("render time      %.3f s\n", st.seconds);
  std::printf(
      "rays             %llu (camera %llu, shadow %llu, reflection %llu, refraction %llu)\n",
      (unsigned long long)st.rays.total(), (unsigned long long)st.rays.camera,
      (unsigned long long)st.rays.shadow, (unsigned long long)st.rays.reflection,
      (unsigned long long)st.rays.refraction);
  std::printf("Mrays/s          %.2f\n",
              st.seconds > 0 ? double(st.rays.total()) / st.seconds * 1e-6 : 0.0);
  std::printf("non-finite       %llu samples\n", (unsigned long long)st.rays.nonfiniteSamples);
  if (st.estimated.rmse)
    std::printf("estimated error  RMSE %.4g, relMSE %.4g (from the render's own samples)\n",
                *st.estimated.rmse, *st.estimated.relmse);
  else
    std::printf("estimated error  none (%s)\n", st.sampler == SamplerKind::Regular
                                                    ? "a regular grid has no randomness"
                                                    : "a pixel has one sample");
  std::printf("samples/pixel    %d to %d, %zu passes (%s sampler)%s\n", st.minPixelSpp,
              st.maxPixelSpp, st.passes.size(), std::string(samplerName(st.sampler)).c_str(),
              st.timeLimitReached ? ", stopped by the time limit" : "");
  std::printf("peak memory      %.1f MB (resident)\n", double(peakResidentBytes()) * 1e-6);
  std::printf("features used    %s\n", join(scene.features.used()).c_str());
  std::printf("left out         %s\n", join(scene.features.leftOut()).c_str());
  // The first names of long lists: --stats-json has them all.
  const auto names = [](const std::vector<std::string>& all) {
    constexpr size_t kShown = 8;
    std::string s;
    for (size_t i = 0; i < all.size() && i < kShown; ++i) s += (i ? ", " : "") + excerpt(all[i]);
    if (all.size() > kShown) s += " and " + std::to_string(all.size() - kShown) + " more";
    return std::to_string(all.size()) + (all.empty() ? "" : ": " + s);
  };
  std::vector<std::string> objects, lights;
  for (const auto& [id, name] : worldObjects(scene)) objects.push_back(name);
  for (size_t k = 0; k < scene.lights.size(); ++k) lights.push_back(scene.lightName(k));
  std::printf("objects          %s\n", names(objects).c_str());
  std::printf("lights           %s\n", names(lights).c_str());
  std::printf("integrator       %s\n", st.integrator == IntegratorKind::Reference
                                           ? "reference (depth first, the oracle)"
                                           : "production (batched)");
}

// The choices of the command line that the frame's record keeps (render/frame_record.h).
FrameSettings frameSettings(const RenderArgs& a) {
  return {a.accel, a.integrator, a.aovs, a.half, a.sampling, commandLine()};
}

// Renders one frame (of an animated scene: `frame`, default its first) and writes its outputs,
// numbered when the scene is animated; with several --crop, each crop to its own -o, from one
// scene load and one acceleration structure. Returns the exit code.
int renderFrame(const RenderArgs& a, std::optional<int> frame) {
  Scene scene = loadSceneOrDefault(a.scenePath, frame, a.camera, a.environment);
  applyOverrides(a, scene);
  // How the render session will spend the samples (it makes the same plan): for the metadata and
  // --resume, and to refuse contradictory bounds before anything is built.
  const PassPlan plan = PassPlan::make(scene.render.spp, scene.render.sampler, a.sampling);
  RenderOptions opt;
  opt.threads = a.threads.value_or(0);
  // The frame's line blocks are compressed on the render's threads: on one, zip would be a
  // serial step as long as a fast render on many cores. Never more than the cores: OpenEXR
  // starts every thread it is given.
  setExrThreads(std::min(threadCount(opt.threads), defaultThreadCount()));
  opt.tileSize = a.tileSize;
  parseIntegratorKind(a.integrator, opt.integrator);
  opt.progress = !a.quiet;
  opt.tileCpuTimes = !a.statsJson.empty();  // the schedule's, for tools/project-scaling.py
  opt.tileOrder = a.tileOrder == "row" ? TileOrder::RowMajor : TileOrder::Morton;
  opt.cancel = &interrupt::requested();
  opt.aovs = AovSet::parse(a.aovs);
  if (a.sampling.progressive && a.resume.empty() && opt.aovs.needsSamples())
    throw UsageError("--resumable keeps the beauty and its variance only, and --aov " + a.aovs +
                     " asks for AOVs whose sums are not kept with the frame: its continuation "
                     "would be refused; drop --resumable, or those AOVs");
  opt.sampling = a.sampling;
  opt.previews = a.previewEvery > 0;
  AccelKind kind = AccelKind::Embree;
  parseAccelKind(a.accel, kind);

  const auto numbered = [&](const std::string& path) {
    return scene.animation ? frameFileName(path, scene.animation->frame) : path;
  };
  struct Job {
    std::optional<PixelWindow> crop;
    std::string out;
  };
  std::vector<Job> jobs;
  for (size_t k = 0; k < std::max<size_t>(1, a.crop.size() / 4); ++k) {
    std::string out = a.outputs.empty() ? std::string() : a.outputs[k];
    if (out.empty())
      out = (a.scenePath.empty() ? std::string("default")
                                 : std::filesystem::path(a.scenePath).stem().string()) +
            (scene.animation ? ".####.exr" : ".exr");
    jobs.push_back({cropWindow(a, scene.render, k), numbered(out)});
  }
  const std::string display = numbered(a.display);
  const std::string stats = a.statsJson == "-" ? a.statsJson : numbered(a.statsJson);
  // Every output (each its own file), and the OCIO config, display, view and look of every
  // display image, are checked before the render is spent on them (their formats were checked
  // with the options, in runRender).
  std::vector<NamedOutput> outputs;
  for (const Job& job : jobs) outputs.push_back({"-o", job.out});
  outputs.push_back({"--display", display});
  outputs.push_back({"--stats-json", stats});
  checkCommandOutputs(outputs);
  const bool displayImages =
      !display.empty() || std::any_of(jobs.begin(), jobs.end(), [](const Job& job) {
        return isDisplayFormat(renderOutputFormat(job.out, {}));
      });
  if (displayImages) DisplayTransform check(a.ocio);
  const auto accel = makeAccelerator(kind, scene, a.accelOptions);
  // From here a signal stops the render and the frame so far is written (CLI.md).
  const interrupt::RenderPhase stopCleanlyOnSignal;
  for (const Job& job : jobs) {
    if (interrupt::requested()) return kExitInterrupted;  // between two crops: none started
    log::info("rendering " + std::to_string(scene.render.width) + "x" +
              std::to_string(scene.render.height) + " " + plan.describe() + " to " + job.out);
    opt.crop = job.crop;
    ResumedFrame resumed;
    std::vector<PassRecord>& earlierPasses = resumed.passes;
    if (!a.resume.empty()) {
      resumed = readResumable(
          a.resume, scene, frameSettings(a), plan,
          job.crop.value_or(PixelWindow{0, scene.render.width, 0, scene.render.height}));
      opt.resumeFrom = &resumed.state;
    }
    // The frame as written: with its state when it may be continued (render/frame_record.h):
    // asked for, or partial (interrupted, a preview), or cut by the time limit, or itself a
    // continuation.
    // A display -o is written only whole: a PNG cannot say it is partial or carry its state.
    const bool displayOut = isDisplayFormat(renderOutputFormat(job.out, {}));
    const bool transparent = scene.render.transparentBackground;
    const auto write = [&](const RenderResult& r, bool partial) -> uint64_t {
      if (displayOut) {
        if (!partial) writeDisplayImage(job.out, r.film, a.ocio, transparent);
        return 0;
      }
      return writeFrameExr(job.out, scene, frameSettings(a), plan, r, partial,
                           {a.half, a.compression, a.multipart}, !a.resume.empty());
    };
    // --preview-every: the frame so far, written as the frame is (atomically), marked partial.
    auto lastPreview = std::chrono::steady_clock::now();
    const PassCallback preview = [&](const RenderResult& soFar) {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - lastPreview).count() < a.previewEvery) return;
      lastPreview = now;
      write(soFar, true);
      if (!display.empty()) writeDisplayImage(display, soFar.film, a.ocio, transparent);
      log::info("preview: " + job.out + " at " + std::to_string(soFar.stats.passes.back().spp) +
                " spp");
    };
    // The frame's passes (render/render_session.h), a preview between two when one is due; a
    // signal cuts the pass in flight (opt.cancel) and the frame keeps the passes finished. The
    // session's buffers are gone before the frame is written.
    RenderResult result = [&] {
      RenderSession session(scene, *accel, opt);
      session.runToEnd(a.previewEvery > 0 ? preview : PassCallback());
      return session.finish();
    }();
    // The earlier render's passes come first; this one's start where its time ended.
    if (!earlierPasses.empty())
      for (PassRecord& p : result.stats.passes) p.seconds += earlierPasses.back().seconds;
    result.stats.passes.insert(result.stats.passes.begin(), earlierPasses.begin(),
                               earlierPasses.end());
    const uint64_t clamped = write(result, result.partial);
    if (clamped > 0)
      log::warning(std::to_string(clamped) + " values beyond " +
                   (a.half ? "half-float's ±65504" : "float's range") +
                   " were clamped to it (glint:clamped_values)");
    if (!display.empty()) writeDisplayImage(display, result.film, a.ocio, transparent);
    if (!stats.empty())
      writeTextFileAtomically(stats, renderStatsJson(scene, result.stats, clamped).dump(2) + "\n");
    if (a.stats) printStats(scene, result.stats);
    if (result.stats.rays.nonfiniteSamples > 0)
      log::warning(std::to_string(result.stats.rays.nonfiniteSamples) +
                   " non-finite samples were dropped (written as black)");
    if (result.partial) {
      // CLI.md: interrupted → a valid partial EXR (each pixel keeps the passes it finished;
      // one that finished none has alpha 0), exit 130.
      log::warning(displayOut ? "interrupted: " + job.out +
                                    " not written (a display image cannot mark a frame partial; "
                                    "-o FRAME.exr keeps partial frames)"
                              : "interrupted: wrote the partial frame " + job.out +
                                    " (glint:partial = 1)");
      return kExitInterrupted;
    }
    if (interrupt::requested()) {
      log::warning("interrupted while writing: " + job.out + " holds the complete frame");
      return kExitInterrupted;
    }
    log::info("wrote " + job.out + (display.empty() ? "" : " and " + display));
  }
  return kExitOk;
}

// Several --crop need one -o each, and leave out the outputs that describe a whole run.
void checkCropsAndOutputs(const RenderArgs& a) {
  const size_t crops = a.crop.size() / 4;
  if (crops <= 1) {
    if (a.outputs.size() > 1)
      throw UsageError("-o is given " + std::to_string(a.outputs.size()) +
                       " times: give one, or one per --crop");
    return;
  }
  if (a.outputs.size() != crops)
    throw UsageError(std::to_string(crops) + " --crop need one -o each, in the same order (got " +
                     std::to_string(a.outputs.size()) + ")");
  if (!a.display.empty() || !a.statsJson.empty() || !a.resume.empty())
    throw UsageError(
        "--display, --stats-json and --resume take one crop: give them with a "
        "single --crop");
}

// Whether --resume's frame drew from the Sobol sequence: then its continuation must too, as a
// --resumable render (the sampler is part of glint:resume_hash, which readResumable checks).
bool drewFromSobol(const std::string& path) {
  return readFrameRecord(path).sampler == SamplerKind::Sobol;
}

// The flags given whose request only an EXR frame can carry (app/render_output.h).
std::vector<std::string> exrOnlyFlags(const RenderArgs& a) {
  std::vector<std::string> flags;
  const auto add = [&](bool given, const char* flag) {
    if (given) flags.emplace_back(flag);
  };
  add(a.half, "--half");
  add(a.multipart, "--multipart");
  add(!a.aovs.empty(), "--aov");
  add(a.compressionGiven, "--compression");
  add(a.sampling.progressive, "--resumable");
  add(a.previewEvery > 0, "--preview-every");
  return flags;
}

int runRender(const RenderArgs& given) {
  // Every image output's format, before anything is loaded.
  for (const std::string& out : given.outputs) renderOutputFormat(out, exrOnlyFlags(given));
  checkIdsSurviveCompression(AovSet::parse(given.aovs).has(Aov::Cryptomatte),
                             {given.half, given.compression, given.multipart});
  if (!given.display.empty()) imageOutputFormat("--display", given.display, ImageOutput::Display);
  RenderArgs a = given;
  if (!a.resume.empty()) allowReplacingInput(a.resume);  // -o may name it (its help)
  if (!a.resume.empty() && drewFromSobol(a.resume)) a.sampling.progressive = true;
  if (a.quiet) log::setLevel(log::Level::Warning);
  checkCropsAndOutputs(a);
  // The outputs as given, before the scene is loaded; renderFrame checks them again as
  // numbered for an animated scene's frame.
  std::vector<NamedOutput> asGiven;
  for (const std::string& out : a.outputs) asGiven.push_back({"-o", out});
  asGiven.push_back({"--display", a.display});
  asGiven.push_back({"--stats-json", a.statsJson});
  checkCommandOutputs(asGiven);
  // Only the frame itself is written back over the frame it continues: --stats-json naming it
  // replaced the frame with JSON.
  if (!a.resume.empty())
    for (const NamedOutput& o : asGiven)
      if (o.option != "-o" && !o.path.empty() && o.path != "-" && nameOneFile(o.path, a.resume))
        throw UsageError(o.option + " " + o.path + " names the frame --resume continues: only -o " +
                         "may write it back");
  // One frame's state continues one frame.
  if (!a.resume.empty() && !a.frames.empty() && parseFrameRange(a.frames, "--frames").count() > 1)
    throw UsageError("--resume continues one frame; --frames " + a.frames +
                     " names several: give --frame N");
  if (a.frames.empty()) return renderFrame(a, a.frame);
  // Several frames in one process: each output must be numbered, or the frames would replace
  // one another.
  const FrameRange range = parseFrameRange(a.frames, "--frames");
  const bool several = range.last > range.first;
  std::vector<std::pair<std::string, std::string>> outputs = {{"--display", a.display},
                                                              {"--stats-json", a.statsJson}};
  for (const std::string& out : a.outputs) outputs.emplace_back("-o", out);
  for (const auto& [option, path] : outputs)
    if (!path.empty() && path != "-" && !hasFrameDigits(path) && several)
      throw UsageError(option + " " + path +
                       " would be overwritten by every frame of --frames: number it with #### "
                       "or %04d");
  if (a.statsJson == "-" && several)
    throw UsageError("--stats-json - with several --frames: give a numbered file instead");
  // The whole range must be the scene's, found before the first frame is spent (and named as
  // given: loaded at the range's first frame, a still scene was reported as "--frame 0").
  const Scene scene = loadSceneOrDefault(a.scenePath, std::nullopt, a.camera, a.environment);
  if (!scene.animation)
    throw UsageError("--frames " + a.frames +
                     ": the scene is not animated (it declares no \"animation\")");
  const FrameRange frames{scene.animation->first, scene.animation->last};
  if (!frames.contains(range.first) || !frames.contains(range.last))
    throw UsageError("--frames " + a.frames + " is outside the scene's frames " +
                     std::to_string(frames.first) + "-" + std::to_string(frames.last));
  for (int frame = range.first; frame <= range.last; ++frame) {
    if (interrupt::requested()) return kExitInterrupted;  // a signal between two frames
    const int code = renderFrame(a, frame);
    if (code != kExitOk) return code;  // interrupted: the frames after it are not started
  }
  return kExitOk;
}

}  // namespace

CommandRunner addRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene to an HDR EXR frame");
  cmd->add_option("scene", args->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->outputs,
                  "Output: .exr the scene-linear frame, .png/.jpg/.tif a display image through the "
                  "OCIO view (default: SCENE_NAME.exr); with several --crop, one each")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      // One path each time it is given: CLI11 let it take the scene after it as a second.
      ->allow_extra_args(false);
  cmd->add_option("--display", args->display,
                  "Also write a display image (.png, .jpg, .tif) through OCIO")
      ->check(nonEmpty());
  addDisplayOptions(*cmd, args->ocio);
  cmd->add_option("--spp", args->spp, "Samples per pixel")
      ->check(CLI::Range(1, static_cast<int>(kMaxSampleSet)));
  cmd->add_option("--target-rmse", args->sampling.target.rmse,
                  "Adaptive sampling: a pixel stops taking samples once its estimated RMSE is "
                  "at most this")
      ->check(positiveNumber());
  cmd->add_option("--target-relmse", args->sampling.target.relmse,
                  "Adaptive sampling: a pixel stops once its estimated relMSE is at most this")
      ->check(positiveNumber());
  cmd->add_option("--time-limit", args->sampling.timeLimitSeconds,
                  "Stop after the last pass that ends within this many seconds of rendering "
                  "(the first pass always finishes)")
      ->check(positiveNumber());
  cmd->add_option("--min-spp", args->sampling.minSpp,
                  "The first pass (default min(" + std::to_string(kDefaultFirstPassSpp) +
                      ", --max-spp)): samples every pixel takes before adaptive sampling or a "
                      "time limit may stop it; without either, the first of the passes that "
                      "double up to the spp (the spp itself: one pass, the same image)")
      ->check(CLI::Range(1, static_cast<int>(kMaxSampleSet)));
  cmd->add_option("--max-spp", args->sampling.maxSpp,
                  "The most samples a pixel may take (default: the spp)")
      ->check(CLI::Range(1, static_cast<int>(kMaxSampleSet)));
  cmd->add_option("--preview-every", args->previewEvery,
                  "Rewrite the output (and --display) with the passes done so far, at most this "
                  "often in seconds")
      ->check(positiveNumber());
  cmd->add_option("--resume", args->resume,
                  "Continue this frame (partial, a preview, time-limited, or --resumable) to "
                  "--spp: the same pixels as a straight render at --spp; -o may name it")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--resumable", args->sampling.progressive,
                "Keep each pixel's sampling state with the frame, so --resume can continue it to "
                "any spp (draws from the Sobol sequence, whose sets do not depend on the spp)");
  cmd->add_option("--seed", args->seed, "Scene seed")->check(wholeNumberUpTo(UINT64_MAX));
  CLI::Option* frame =
      cmd->add_option("--frame", args->frame,
                      "Frame of an animated scene (default: its first); -o NAME.####.exr or "
                      "NAME.%04d.exr numbers the file");
  cmd->add_option("--camera", args->camera,
                  "A camera of a glTF, Collada, FBX or AC3D scene, by name (default: its first)");
  cmd->add_option("--environment", args->environment,
                  "A lat-long image (EXR, .hdr) lighting a mesh-file scene as an environment "
                  "light, in place of its default light");
  cmd->add_option("--frames", args->frames,
                  "Frames A-B of an animated scene, one after another in this process")
      ->check(nonEmpty())
      ->excludes(frame);
  cmd->add_option("--threads", args->threads, "Render threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--width", args->width, "Image width")->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--height", args->height, "Image height")->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--max-depth", args->maxDepth, "Recursion limit")->check(CLI::Range(0, 1000));
  cmd->add_option("--accel", args->accel,
                  "Intersection backend (default " + defaultText(args->accel) + ")")
      ->check(CLI::IsMember({"embree", "bvh", "brute", "grid", "octree", "kdtree",
                             "octree-generate-and-test", "rayclass", "coherence", "spheres"}));
  addAccelOptions(*cmd, args->accelOptions);
  cmd->add_option("--integrator", args->integrator,
                  "production, or reference: seed 002's depth-first Trace, the oracle the "
                  "production kernel is tested against (beauty only) (default " +
                      defaultText(args->integrator) + ")")
      ->check(CLI::IsMember({"production", "reference"}));
  cmd->add_option("--sampler", args->sampler, "Pixel sampler (overrides the scene)")
      ->check(CLI::IsMember({"regular", "random", "stratified", "sobol"}));
  takesValues(*cmd,
              cmd->add_option("--crop", args->crop,
                              "Pixel bounds X0 X1 Y0 Y1 ([X0,X1) x [Y0,Y1)); repeat it, each with "
                              "its own -o, to render several crops from one scene load"),
              4, ValueKind::Integer, "X0 X1 Y0 Y1")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--tile-size", args->tileSize,
                  "Tile edge in pixels (default " + defaultText(args->tileSize) + ")")
      ->check(CLI::Range(1, 4096));
  cmd->add_option(
         "--tile-order", args->tileOrder,
         "Tile order, the image the same for any (default " + defaultText(args->tileOrder) + ")")
      ->check(CLI::IsMember({"morton", "row"}));
  cmd->add_flag("--half", args->half, "Half-float beauty (default float)");
  cmd->add_flag("--transparent-background", args->transparentBackground,
                "Camera rays that miss leave RGB 0, alpha 0 (default: the background is opaque)");
  cmd->add_option("--aov", args->aovs,
                  "AOVs, comma separated: depth,normal,albedo,position,objectid,direct,indirect,"
                  "lights,variance,cryptomatte")
      ->check(CLI::Validator(
          [](std::string& list) {
            // "" and "," rendered no AOV without a word; unknown names are refused by name
            // where the list is read (AovSet::parse).
            return list.find_first_not_of(',') == std::string::npos
                       ? std::string("must name at least one AOV")
                       : std::string();
          },
          "LIST"));
  cmd->add_flag("--multipart", args->multipart, "One EXR part per AOV (default: layers in one)");
  CLI::Option* compression =
      cmd->add_option("--compression", args->compression,
                      "EXR compression (default " + defaultText(args->compression) + ")")
          ->check(CLI::IsMember(exrCompressions()));
  cmd->add_flag("--stats", args->stats, "Print render statistics");
  cmd->add_option("--stats-json", args->statsJson, "Write render statistics as JSON")
      ->check(nonEmpty());
  cmd->add_flag("--quiet", args->quiet, "No progress or info messages");
  return [args, compression, &app] {
    (void)app;
    args->compressionGiven = compression->count() > 0;
    return runRender(*args);
  };
}

}  // namespace glint
