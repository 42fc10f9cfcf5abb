#pragma once
// `glint bench --intersection-share`: the share of a render's time that goes to intersection,
// for each backend. Seed 002 §9.2 ("Practical observations show that 75–95% of calculation time
// is spent on intersection calculations during ray tracing") is the claim it checks. The render
// is not timed call by call (a clock read costs as much as a short traversal and would change
// what it measures): one thread renders the scene with the backend, best of `runs`; the same
// render's queries, recorded by RayRecorder in an untimed render, are replayed through the
// backend alone on one thread, in the render's order and batches, best of `runs`; the share is
// replay seconds / render seconds (docs/acceleration.md). Both are the thread's CPU time, which
// other processes on a shared machine do not inflate.
#include <nlohmann/json.hpp>
#include <vector>

#include "accel/accelerator.h"
#include "scene/scene.h"

namespace glint {

// Prints one line per backend and returns {"intersection_share": {name: {...}}}; `options`
// are the backends' settings (ray classification's n_min and w_min).
nlohmann::json studyIntersectionShare(const Scene& scene, const std::vector<AccelKind>& kinds,
                                      int runs, const AccelOptions& options = {});

}  // namespace glint
