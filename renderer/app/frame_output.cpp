#include "app/frame_output.h"

#include "core/memory.h"

namespace glint {

namespace {

// An estimate, or null where there is none (one sample, a regular grid).
nlohmann::json orNull(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

// Where the render's time went around its parallel phases (render/pass_timing.h), for
// tools/project-scaling.py: each phase's tiles as [tile, start, seconds, thread, CPU seconds], in
// the order taken.
nlohmann::json scheduleJson(const RenderTiming& t) {
  nlohmann::json phases = nlohmann::json::array();
  for (const PassTiming& p : t.passes) {
    nlohmann::json tiles = nlohmann::json::array();
    for (const TileTime& tile : p.tiles)
      tiles.push_back({tile.tile, tile.start, tile.seconds, tile.thread, tile.cpuSeconds});
    phases.push_back({{"spp", p.spp},
                      {"loop_seconds", p.loopSeconds},
                      {"serial_seconds", p.serialSeconds},
                      {"tiles_seconds", p.tilesSeconds},
                      {"tiles", std::move(tiles)}});
  }
  return {{"threads", t.threads},
          {"pixels", {t.width, t.height}},
          {"tile_size", t.tileSize},
          {"setup_seconds", t.setupSeconds},
          {"init_seconds", t.initSeconds},
          {"phases", std::move(phases)},
          {"finish_loop_seconds", t.finishLoopSeconds},
          {"finish_seconds", t.finishSeconds}};
}

}  // namespace

uint64_t writeFrameExr(const std::string& path, const Scene& scene, const FrameSettings& settings,
                       const PassPlan& plan, const RenderResult& result, bool partial,
                       const ExrOptions& options, bool continued) {
  const FrameRecord record = frameRecord(scene, settings, plan, result, partial);
  ExrMetadata m;
  writeFrameRecord(record, m);
  const bool resumable =
      settings.sampling.progressive || partial || result.stats.timeLimitReached || continued;
  if (!resumable) return writeExr(path, result.film, m, options);
  Film withState = result.film;
  writeResumeState(withState, m, result.estimates, result.position, record);
  return writeExr(path, withState, m, options);
}

std::vector<std::pair<uint32_t, std::string>> worldObjects(const Scene& scene) {
  const std::vector<bool> inWorld = scene.objectIdsInWorld();
  std::vector<std::pair<uint32_t, std::string>> objects;
  for (uint32_t i = 0; i < inWorld.size(); ++i)
    if (inWorld[i]) objects.emplace_back(i + 1, scene.objectName(i));
  return objects;
}

nlohmann::json renderStatsJson(const Scene& scene, const RenderStats& st, uint64_t clampedValues) {
  nlohmann::json j;
  j["seconds"] = st.seconds;
  j["rays_total"] = st.rays.total();
  j["rays"] = {{"camera", st.rays.camera},
               {"shadow", st.rays.shadow},
               {"reflection", st.rays.reflection},
               {"refraction", st.rays.refraction}};
  j["nonfinite_samples"] = st.rays.nonfiniteSamples;
  j["clamped_values"] = clampedValues;  // beyond the EXR channel type's range (writeExr)
  j["features_used"] = scene.features.used();
  j["features_left_out"] = scene.features.leftOut();
  j["objects"] = nlohmann::json::array();
  for (const auto& [id, name] : worldObjects(scene))
    j["objects"].push_back({{"id", id}, {"name", name}});
  j["lights"] = nlohmann::json::array();
  for (size_t k = 0; k < scene.lights.size(); ++k) j["lights"].push_back(scene.lightName(k));
  j["integrator"] = st.integrator == IntegratorKind::Reference ? "reference" : "production";
  j["sampler"] = samplerName(st.sampler);
  // The estimates of the frame's error from its own samples (docs/validation.md).
  j["estimated_rmse"] = orNull(st.estimated.rmse);
  j["estimated_relmse"] = orNull(st.estimated.relmse);
  j["passes"] = nlohmann::json::parse(passesJson(st.passes));  // as glint:passes holds them
  j["pixel_spp"] = {{"min", st.minPixelSpp}, {"max", st.maxPixelSpp}};
  j["time_limit_reached"] = st.timeLimitReached;
  j["schedule"] = scheduleJson(st.timing);
  // Of the whole process up to now: scene, acceleration structure, film and the EXR written.
  j["peak_rss_bytes"] = peakResidentBytes();
  return j;
}

}  // namespace glint
