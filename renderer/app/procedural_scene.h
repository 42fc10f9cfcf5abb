#pragma once
// A procedural benchmark scene of about `triangles` triangles: a rolling heightfield (sums of
// sines) with a sphere on it, one point light, a camera looking across. Deterministic.
#include <cstddef>

#include "scene/scene.h"

namespace glint {

Scene makeProceduralScene(size_t triangles);

}  // namespace glint
