// `glint converge SCENE`: error against run time over a series of sample counts, per sampler and
// backend, against a reference rendered with an independent seed (or given as an EXR).
// `glint converge --from-render FRAME.exr`: the same from one render's passes and its own error
// estimates (glint:passes), with nothing rendered.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/commands.h"
#include "app/convergence_plot.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/input_files.h"
#include "core/json_memory.h"
#include "core/log.h"
#include "core/sampler.h"
#include "film/atomic_file.h"
#include "film/compare.h"
#include "film/exr_input.h"
#include "film/image_format.h"
#include "render/frame_record.h"
#include "render/render_job.h"

namespace glint {

namespace {

// A rendered reference takes this many times the largest spp of the series, unless told.
constexpr int kReferenceSppFactor = 16;

struct ConvergeArgs {
  std::string scenePath;
  std::string spp = "1,2,4,8,16,32,64";
  std::optional<std::string> samplers;  // default: the scene's
  std::string accels = "embree";
  std::string reference;
  int referenceSpp = 0;  // default: kReferenceSppFactor × the largest spp
  std::optional<int> width, height;
  int threads = 0;
  std::string csv, plot, json;
  std::string fromRender;  // an EXR written by glint render, or its --stats-json
};

// The names of a comma-separated list, blank ones skipped; a list naming nothing is refused
// (`--spp ,` would otherwise leave no series to render).
std::vector<std::string> split(const std::string& s, const char* option, const char* what) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string t; std::getline(in, t, ',');)
    if (!t.empty()) out.push_back(t);
  if (out.empty()) throw UsageError(std::string(option) + ": name at least one " + what);
  return out;
}

Image renderImage(const Scene& scene, const Accelerator& accel, int threads, double& wall,
                  double& cpu) {
  RenderOptions opt;
  opt.threads = threads;
  opt.progress = false;
  const std::clock_t c0 = std::clock();
  const RenderResult r = renderScene(scene, accel, opt);
  cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  wall = r.stats.seconds;
  return imageFromFilm(r.film);
}

// The series as --csv, --plot and --json ask; `about` opens the JSON object.
void writeOutputs(const ConvergeArgs& a, const std::vector<ConvergenceSeries>& series,
                  const std::string& title, const nlohmann::json& about) {
  if (!a.csv.empty()) {
    std::string csv = "series,spp,seconds,cpu_seconds,rmse,relmse\n";
    for (const auto& s : series)
      for (const auto& p : s.points) {
        char line[256];
        std::snprintf(line, sizeof line, "%s,%d,%.6f,%.6f,%.8g,%.8g\n", s.name.c_str(), p.spp,
                      p.seconds, p.cpuSeconds, p.rmse, p.relmse);
        csv += line;
      }
    writeTextFileAtomically(a.csv, csv);
  }
  if (!a.plot.empty()) writeConvergenceSvg(a.plot, title, series);
  if (!a.json.empty()) {
    nlohmann::json j = about;
    for (const auto& s : series) {
      nlohmann::json js{{"name", s.name}, {"slope", s.slope}, {"spp_slope", s.sppSlope}};
      for (const auto& p : s.points)
        js["points"].push_back({{"spp", p.spp},
                                {"seconds", p.seconds},
                                {"cpu_seconds", p.cpuSeconds},
                                {"rmse", p.rmse},
                                {"relmse", p.relmse}});
      j["series"].push_back(js);
    }
    writeTextFileAtomically(a.json, j.dump(2) + "\n");
  }
}

// The passes a render recorded: the `passes` of its --stats-json, or its EXR's glint:passes,
// read as the frame record reads them (render/frame_record.h).
std::vector<PassRecord> passesOf(const std::string& path) {
  const bool isJson = path.size() > 5 && path.substr(path.size() - 5) == ".json";
  if (!isJson) {
    const FrameRecord record = readFrameRecord(path);
    if (!record.passes)
      throw UsageError(path +
                       " has no glint:passes: it was not written by a glint render that "
                       "records its passes");
    return *record.passes;
  }
  const std::string text = readInputFile(path, size_t{64} << 20, "render record (--stats-json)");
  checkJsonTreeFits(text, 0, 0, "render record " + path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw UsageError(path + ": its JSON is not JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    // A number past a double's range (1e999) is no parse error to nlohmann but out_of_range.
    throw UsageError(path + ": its JSON holds a value Glint cannot read (" + excerpt(e.what()) +
                     ")");
  }
  if (!j.is_object() || !j.contains("passes") || !j["passes"].is_array())
    throw UsageError(path + ": has no \"passes\" list");
  return parsePasses(path, "passes", j["passes"]);
}

// A pass with its estimated error: one of a render of one sample, or of the regular sampler,
// has none to plot.
ConvergencePoint passPoint(const std::string& path, size_t index, const PassRecord& pass) {
  if (!pass.estimated.rmse || !pass.estimated.relmse)
    throw UsageError(path + ": passes[" + std::to_string(index) +
                     "] has no error estimate (a render of one sample, or of the regular "
                     "sampler, has nothing to estimate from)");
  ConvergencePoint p;
  p.spp = pass.spp;
  p.seconds = pass.seconds;
  p.rmse = *pass.estimated.rmse;
  p.relmse = *pass.estimated.relmse;
  return p;
}

// --from-render: one series, the render's passes with their estimated errors.
int convergeFromRender(const ConvergeArgs& a) {
  ConvergenceSeries s;
  s.name = "estimated";
  const std::vector<PassRecord> passes = passesOf(a.fromRender);
  for (size_t i = 0; i < passes.size(); ++i) {
    const ConvergencePoint point = passPoint(a.fromRender, i, passes[i]);
    s.points.push_back(point);
    std::printf("pass to spp %6d  %9.4f s  estimated rmse %.6g  relmse %.6g\n", point.spp,
                point.seconds, point.rmse, point.relmse);
  }
  if (s.points.empty()) throw UsageError(a.fromRender + " records no finished pass");
  fitSlopes(s);
  std::printf("estimated          slope %s against seconds, %s against spp\n",
              slopeText(s.slope).c_str(), slopeText(s.sppSlope).c_str());
  writeOutputs(a, {s}, "Estimated error against time: " + a.fromRender,
               {{"from_render", a.fromRender}});
  return kExitOk;
}

int runConverge(const ConvergeArgs& a) {
  if (!a.plot.empty()) imageOutputFormat("--plot", a.plot, ImageOutput::Plot);
  // The inputs are noted first, so that an output naming one is refused before the series is
  // rendered, not after.
  for (const std::string* input : {&a.scenePath, &a.reference, &a.fromRender})
    if (!input->empty()) noteInputFile(*input);
  checkCommandOutputs({{"--csv", a.csv}, {"--plot", a.plot}, {"--json", a.json}});
  if (!a.fromRender.empty()) return convergeFromRender(a);
  Scene scene = loadSceneOrDefault(a.scenePath);
  if (a.width) scene.render.width = *a.width;
  if (a.height) scene.render.height = *a.height;
  std::vector<int> spps;
  for (const auto& s : split(a.spp, "--spp", "sample count")) {
    // The whole text must be the number: std::stoi read "1e999" and "1.5" as 1.
    int v = 0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (error != std::errc() || end != s.data() + s.size() || s.empty())
      throw UsageError("--spp: " + inQuotes(s) + " is not a sample count");
    if (v < 1) throw UsageError("--spp: sample counts must be ≥ 1");
    if (v > kMaxSampleSet)
      throw UsageError("--spp: " + s + " is more than the sampler's limit of " +
                       std::to_string(kMaxSampleSet));
    spps.push_back(v);
  }
  std::vector<SamplerKind> samplers;
  for (const auto& s :
       a.samplers ? split(*a.samplers, "--sampler", "sampler") : std::vector<std::string>{}) {
    SamplerKind k;
    if (!parseSamplerKind(s, k)) throw UsageError("--sampler: unknown sampler " + inQuotes(s));
    samplers.push_back(k);
  }
  if (samplers.empty()) samplers.push_back(scene.render.sampler);
  std::vector<AccelKind> accels;
  for (const auto& s : split(a.accels, "--accel", "backend")) {
    AccelKind k;
    if (!parseAccelKind(s, k)) throw UsageError("--accel: unknown backend " + inQuotes(s));
    accels.push_back(k);
  }

  // The reference: given, or rendered with an independent seed so that it shares no samples
  // with the renders being measured.
  Image reference;
  nlohmann::json referenceInfo;  // what the errors are measured against, for the outputs
  std::string referenceLabel;
  if (!a.reference.empty()) {
    reference = readImage(a.reference);
    requireFiniteReference(reference, a.reference);
    referenceInfo = {{"file", a.reference}};
    referenceLabel = "reference " + a.reference;
  } else {
    Scene refScene = scene;
    refScene.render.seed = mix64(scene.render.seed ^ 0x5eedf00dULL);
    // In 64 bits: 16 × a large --spp passes int's range.
    const int64_t spp =
        a.referenceSpp > 0
            ? a.referenceSpp
            : kReferenceSppFactor * int64_t{*std::max_element(spps.begin(), spps.end())};
    if (spp > kMaxSampleSet)
      throw UsageError("the reference would take " + std::to_string(kReferenceSppFactor) +
                       " × the largest --spp = " + std::to_string(spp) +
                       " spp, more than the sampler's limit of " + std::to_string(kMaxSampleSet) +
                       ": give --reference-spp or --reference");
    refScene.render.spp = static_cast<int>(spp);
    refScene.render.sampler = SamplerKind::Stratified;
    log::info("rendering the reference at " + std::to_string(refScene.render.spp) + " spp");
    const auto accel = makeAccelerator(AccelKind::Embree, refScene);
    double wall, cpu;
    reference = renderImage(refScene, *accel, a.threads, wall, cpu);
    referenceInfo = {{"spp", refScene.render.spp},
                     {"seed", refScene.render.seed},
                     {"sampler", samplerName(refScene.render.sampler)}};
    referenceLabel = "reference " + std::to_string(refScene.render.spp) + " spp";
  }
  const std::string size =
      std::to_string(scene.render.width) + "×" + std::to_string(scene.render.height);

  std::vector<ConvergenceSeries> series;
  bool placementSaid = false;  // of the reference, once
  for (AccelKind ak : accels) {
    const auto accel = makeAccelerator(ak, scene);
    for (SamplerKind sk : samplers) {
      ConvergenceSeries s;
      s.name = std::string(samplerName(sk)) +
               (accels.size() > 1 ? "/" + std::string(accelName(ak)) : "");
      for (int spp : spps) {
        scene.render.sampler = sk;
        scene.render.spp = spp;
        ConvergencePoint p;
        p.spp = spp;
        const Image img = renderImage(scene, *accel, a.threads, p.seconds, p.cpuSeconds);
        const ImageErrors e =
            compareImages(img, reference, kDefaultCompareThreshold,
                          {"the " + s.name + " render at " + std::to_string(spp) + " spp",
                           a.reference.empty() ? "the reference" : a.reference});
        if (!e.placement.empty() && !placementSaid) log::warning(e.placement);
        placementSaid = placementSaid || !e.placement.empty();
        p.rmse = e.rmse;
        p.relmse = e.relmse;
        s.points.push_back(p);
        std::printf("%-18s spp %6d  %9.4f s wall %9.4f s cpu  rmse %.6g  relmse %.6g\n",
                    s.name.c_str(), spp, p.seconds, p.cpuSeconds, p.rmse, p.relmse);
      }
      fitSlopes(s);
      std::printf("%-18s slope %s against seconds, %s against spp\n", s.name.c_str(),
                  slopeText(s.slope).c_str(), slopeText(s.sppSlope).c_str());
      series.push_back(std::move(s));
    }
  }

  writeOutputs(a, series,
               "Error against time: " + scene.sourcePath + ", " + size + ", " + referenceLabel,
               {{"scene", scene.sourcePath},
                {"width", scene.render.width},
                {"height", scene.render.height},
                {"reference", referenceInfo}});
  return kExitOk;
}

}  // namespace

CommandRunner addConvergeCommand(CLI::App& app) {
  auto a = std::make_shared<ConvergeArgs>();
  CLI::App* cmd = app.add_subcommand("converge", "Error against run time over sample counts");
  cmd->add_option("scene", a->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("--spp", a->spp, "Sample counts, comma separated (default " + a->spp + ")");
  cmd->add_option("--sampler", a->samplers, "Samplers to compare, comma separated");
  cmd->add_option("--accel", a->accels,
                  "Backends to compare, comma separated (default " + a->accels + ")");
  cmd->add_option("--reference", a->reference, "Reference EXR (default: rendered)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--reference-spp", a->referenceSpp,
                  "Samples of the rendered reference (default " +
                      std::to_string(kReferenceSppFactor) + " × the largest spp)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--width", a->width, "Override the scene's width")->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--height", a->height, "Override the scene's height")
      ->check(CLI::Range(1, 1 << 15));
  cmd->add_option("--threads", a->threads, "Render threads (default: all)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--from-render", a->fromRender,
                  "No renders: the passes of one render (its EXR, or its --stats-json) with the "
                  "error it estimated after each")
      ->check(CLI::ExistingFile);
  cmd->add_option("--csv", a->csv, "Write every point as CSV")->check(nonEmpty());
  cmd->add_option("--plot", a->plot, "Write the log-log plot (SVG)")->check(nonEmpty());
  cmd->add_option("--json", a->json, "Write the series as JSON")->check(nonEmpty());
  return [a] { return runConverge(*a); };
}

}  // namespace glint
