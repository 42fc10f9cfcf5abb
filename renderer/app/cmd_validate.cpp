// `glint validate`: renders the scene's own rays (camera, reflection, refraction, shadow) and
// N random rays through Embree, the reference BVH, the uniform grid, the octree, the k-d tree,
// ray classification, the sphere hierarchy and (for small scenes) brute force, and reports how
// well they agree, hit by hit.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "accel/cross_check.h"
#include "app/accel_options.h"
#include "app/commands.h"
#include "app/option_arity.h"
#include "app/scene_source.h"
#include "app/scene_validation.h"
#include "core/error.h"
#include "film/atomic_file.h"

namespace glint {

namespace {

struct ValidateArgs : ValidateSettings {
  std::string scenePath;
  double minAgreement = 1 - 1e-6;
  std::string json;
  std::vector<std::string> ray;  // --ray's nine numbers
  bool occludedRay = false;
};

int runValidate(const ValidateArgs& a) {
  checkCommandOutputs({{"--json", a.json}});
  if (a.ray.empty()) checkSomethingIsCast(a);  // --ray casts its one ray
  Scene scene = loadSceneOrDefault(a.scenePath);
  const ValidationBackends backends(scene, a);
  if (!a.ray.empty()) {  // reproduce one ray from a report line
    Ray r;
    std::string text;
    for (const std::string& v : a.ray) text += v + " ";
    if (!parseRay(text, r))
      throw UsageError("--ray: expected 9 numbers: ox oy oz dx dy dz tmin tmax time");
    if (const std::string why = rayProblem(r); !why.empty()) throw UsageError("--ray: " + why);
    std::printf("ray %s\n", formatRay(r).c_str());
    std::vector<const Accelerator*> all{&backends.embree};
    for (const Accelerator* acc : backends.others()) all.push_back(acc);
    for (const Accelerator* acc : all)
      std::printf("  %-24s %s\n", std::string(acc->name()).c_str(),
                  a.occludedRay ? (acc->occluded(r) ? "occluded" : "clear")
                                : formatHit(acc->intersect(r)).c_str());
    return kExitOk;
  }

  const nlohmann::json j = validateScene(scene, backends, a, true);
  if (!a.json.empty()) writeTextFileAtomically(a.json, j.dump(2) + "\n");
  const double hits = j["hit_agreement"], occlusion = j["occlusion_agreement"];
  if (hits < a.minAgreement || occlusion < a.minAgreement) {
    std::fprintf(stderr, "glint: validation failed: agreement below %.9f\n", a.minAgreement);
    return kExitRuntime;
  }
  return kExitOk;
}

}  // namespace

CommandRunner addValidateCommand(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Cross-check Embree against the reference BVH and the uniform grid (and brute force), hit "
      "by hit");
  cmd->add_option("scene", args->scenePath, sceneArgumentHelp())->check(CLI::ExistingFile);
  cmd->add_option("--rays", args->rays, "Random rays besides the scene's own")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_option("--seed", args->seed, "Seed of the random rays")
      ->check(wholeNumberUpTo(UINT64_MAX));
  cmd->add_option("--spp", args->spp,
                  "Camera samples per pixel for the scene's rays (0: random rays only)")
      ->check(CLI::Range(0, 1 << 16));
  cmd->add_option("--min-agreement", args->minAgreement,
                  "Fail (exit 1) when hit/miss or occlusion agreement is below this")
      ->check(CLI::Range(0.0, 1.0) & notNaN());
  cmd->add_option("--json", args->json, "Write the figures as JSON")->check(nonEmpty());
  takesValues(*cmd,
              cmd->add_option("--ray", args->ray,
                              "Trace one ray: nine numbers, as separate arguments or one quoted "
                              "\"ox oy oz dx dy dz tmin tmax time\" (a report line's)"),
              9, ValueKind::Number, "ox oy oz dx dy dz tmin tmax time");
  cmd->add_flag("--occluded", args->occludedRay, "With --ray: an occlusion query");
  cmd->add_flag("--no-brute", args->noBrute, "Skip the brute-force oracle");
  addAccelOptions(*cmd, args->accelOptions);
  return [args] { return runValidate(*args); };
}

}  // namespace glint
