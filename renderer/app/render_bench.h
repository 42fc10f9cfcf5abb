#pragma once
// Whole-render figures for `glint bench`: rays by kind and rates, the Embree-limit ratio (the
// render's rays replayed through Embree alone), a time split, the gain of the specialised
// integrator over the general one, and memory per triangle. Parallel efficiency and tile sizes
// are timed by cmd_bench.cpp with bestRenderSeconds.
#include <nlohmann/json.hpp>

#include "accel/embree_accel.h"
#include "scene/scene.h"

namespace glint {

struct RenderBenchOptions {
  int threads = 1;  // for the timed renders and replays
  int runs = 3;     // each figure is the best of this many (the machine is shared)
};

// Prints the figures and returns them as JSON (keys in docs/performance.md).
nlohmann::json benchWholeRender(const Scene& scene, const EmbreeAccel& embree,
                                const RenderBenchOptions& opt);

// The fastest of `runs` whole renders (no progress output), in seconds.
double bestRenderSeconds(const Scene& scene, const Accelerator& accel, int threads, int tileSize,
                         int runs);

// Bytes the scene's triangle meshes hold (positions, keys, indices) plus Embree's BVHs.
int64_t sceneGeometryBytes(const Scene& scene, const EmbreeAccel& embree);

}  // namespace glint
