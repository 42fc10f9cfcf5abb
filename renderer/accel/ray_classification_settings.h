#pragma once
// What may be set of the ray classification backend (accel/ray_classification.h), from the
// command line's --rayclass-n-min and --rayclass-w-min (app/accel_options.h).
#include <cstddef>
#include <cstdint>

namespace glint {

struct RayClassSettings {
  // Seed 002 §9.2.3's thresholds: a cell is not split when its candidate list holds at most
  // nMin objects, or when it is at most wMin wide (its narrowest of the five axes, the cube E
  // around the group scaled to a unit cube and the direction coordinates spanning [−1, 1]); a
  // w_min below 10⁻⁶ is taken as 10⁻⁶. The defaults are the fastest per camera ray of
  // docs/acceleration.md's measurement.
  uint32_t nMin = 8;
  double wMin = 1.0 / 512;
  // Bytes the lazily made cells and candidate lists may take, over all groups (0: the default
  // cap, RayClassification::defaultCapBytes).
  size_t capBytes = 0;
  // Beam tests the lazily made cells may cost, over all groups (0: 256 per reference of
  // referenceBudget, accel/primitives.h): the work bound, as capBytes is the memory bound.
  size_t testBudget = 0;
};

}  // namespace glint
