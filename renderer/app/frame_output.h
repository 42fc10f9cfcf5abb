#pragma once
// What a render leaves besides its pixels in memory: the EXR frame with its record (and the
// state --resume continues from, where the frame may be continued), and the statistics as
// `--stats-json` writes them. `glint render` and the Python module (python/) both write
// through here, so that a frame rendered from Python is the file the command writes.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "film/exr_output.h"
#include "render/frame_record.h"
#include "render/pass_plan.h"
#include "render/render_job.h"
#include "scene/scene.h"

namespace glint {

// Writes `result`, a render of `scene` with `settings` by `plan`, to `path` as an EXR with its
// frame record. The frame keeps its resume state when it may be continued: asked for
// (settings.sampling.progressive), partial, cut by the time limit, or itself a continuation
// (`continued`). Returns the values clamped to the channel type's range (writeExr).
uint64_t writeFrameExr(const std::string& path, const Scene& scene, const FrameSettings& settings,
                       const PassPlan& plan, const RenderResult& result, bool partial,
                       const ExrOptions& options, bool continued = false);

// The render statistics as `--stats-json` writes them (CLI.md): `clampedValues` as writeFrameExr
// returned it.
nlohmann::json renderStatsJson(const Scene& scene, const RenderStats& stats,
                               uint64_t clampedValues);

// The objects of the world by id (the objectid AOV's id, objects' id + 1) and name, as the
// manifests list them.
std::vector<std::pair<uint32_t, std::string>> worldObjects(const Scene& scene);

}  // namespace glint
