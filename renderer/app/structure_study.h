#pragma once
// `glint bench --structures`: the study seed 000 §12.3 and seed 002 §9.2 invite. For each
// acceleration structure, its build time and memory, and its single-thread time per ray on the
// scene's camera rays and on random rays, and for Glint's own structures the nodes or cells
// each ray visits and the primitives it tests (the quantities the seeds' claims are about), so a
// series of scenes of growing n shows how each structure's cost grows (tools/accel_study.py
// runs the series and plots it). Ray classification builds while tracing: its memory is taken
// after the rays, with the cells and bytes it had made after each set, and every structure's
// first pass is kept beside its best.
#include <nlohmann/json.hpp>
#include <vector>

#include "accel/accelerator.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace glint {

// Prints one line per structure and returns {"primitives", "structures": {name: {...}}}.
nlohmann::json studyStructures(const Scene& scene, const std::vector<AccelKind>& kinds,
                               const std::vector<Ray>& cameraRays,
                               const std::vector<Ray>& randomRays,
                               const AccelOptions& options = {});

}  // namespace glint
