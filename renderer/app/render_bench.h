#pragma once
// Whole-render figures for `glint bench`: rays by kind and rates, the Embree-limit ratio (the
// render's rays replayed through Embree alone), a time split, the gain of the specialised
// integrator over the general one, and memory per triangle. Parallel efficiency and tile sizes
// are timed by cmd_bench.cpp with bestRenderSeconds.
#include <nlohmann/json.hpp>

#include "accel/embree_accel.h"
#include "accel/ray_recorder.h"
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

// The rays a render traced (RayRecorder), through `accel` with no shading, on `threads` threads:
// seconds per pass over them, `passes` times over (so that a replay can last about as long as
// the render it is compared with, and meet the same moments of a shared machine). One ray at a
// time (intersect / occluded: for Embree the Embree limit of the issue), or `asTraced`: each
// query as the render made it, a coherent batch through intersectCoherent / occludedCoherent
// (Embree's packets), which is the traversal the render itself pays.
double replaySeconds(const Accelerator& accel, const std::vector<RecordedRay>& rays, int threads,
                     bool asTraced, int passes);

// Bytes the scene's triangle meshes hold (positions, keys, indices) plus Embree's BVHs.
int64_t sceneGeometryBytes(const Scene& scene, const EmbreeAccel& embree);

}  // namespace glint
