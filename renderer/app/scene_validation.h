#pragma once
// What `glint validate` measures, for the command and the Python module (glint.validate): the
// scene's own rays and random rays through Embree and every other backend, hit by hit.
#include <cstdint>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/brute_force.h"
#include "accel/embree_accel.h"
#include "accel/kd_tree.h"
#include "accel/octree.h"
#include "accel/ray_classification.h"
#include "accel/ray_coherence.h"
#include "accel/reference_bvh.h"
#include "accel/sphere_hierarchy.h"
#include "accel/uniform_grid.h"
#include "scene/scene.h"

namespace glint {

struct ValidateSettings {
  int rays = 100000;  // random rays besides the scene's own
  uint64_t seed = 1;  // of the random rays
  int spp = 1;        // camera samples per pixel for the scene's rays (0: random rays only)
  bool noBrute = false;
  AccelOptions accelOptions;
};

// Brute force is O(N) per ray: used when the scene has at most this many primitives.
constexpr size_t kBruteForceLimit = 5000;

// Throws UsageError where the settings cast no ray (--rays 0 with --spp 0): an agreement of 1
// over no query passed every threshold. Called before the backends are built.
void checkSomethingIsCast(const ValidateSettings& settings);

// Every backend of `scene`, built once: Embree, and the others checked against it.
struct ValidationBackends {
  ValidationBackends(const Scene& scene, const ValidateSettings& settings);
  std::vector<const Accelerator*> others() const;  // all but Embree, brute force last

  const EmbreeAccel embree;
  const ReferenceBvh bvh;
  const UniformGrid grid;
  const Octree octree;
  const Octree octreeGenerateAndTest;
  const KdTree kdtree;
  const RayClassification rayclass;
  const RayCoherence coherence;
  const SphereHierarchy spheres;
  std::unique_ptr<BruteForce> brute;  // null for a large scene, or --no-brute
};

// Casts the scene's rays (at settings.spp, which it sets in scene.render: no copy of a big mesh's
// scene) and the random rays through every backend; prints the report on standard output when
// `print`; returns the figures (`glint validate --json`). Throws UsageError when the distances
// kept would not fit in memory.
nlohmann::json validateScene(Scene& scene, const ValidationBackends& backends,
                             const ValidateSettings& a, bool print);

}  // namespace glint
