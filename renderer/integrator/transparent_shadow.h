#pragma once
// Shadow rays through transparent objects (seed 002 §9.1): a shadow ray that meets only
// dielectrics carries the product of their transmissions k_t, the Fresnel transmittance 1 − R
// (or a constant k_t, materials/dielectric.h) at each interface and Beer's law over each
// distance inside, instead of being blocked.
// As the seed says, the shadow ray itself is not refracted: it runs straight to the light.
// Both integrators call this; it traces one ray at a time.
#include "accel/accelerator.h"
#include "core/rgb.h"
#include "integrator/medium_stack.h"
#include "integrator/ray_counters.h"
#include "scene/scene.h"

namespace glint {

// After this many interfaces a shadow ray gives up and counts the light as blocked.
inline constexpr int kMaxShadowInterfaces = 64;

// The fraction of a light's intensity that arrives along `shadow`, a shadow ray as spawned from
// the shading point (towards a point, or to infinity when atInfinity), which starts inside the
// objects of `media` (the interior list of the ray that reached the point). Any opaque surface
// blocks it; so does a transmission below minThroughput in every channel.
Rgb transparentShadow(const Scene& scene, const Accelerator& accel, Ray shadow, bool atInfinity,
                      MediumStack media, float minThroughput, RayCounters& counters);

}  // namespace glint
