#pragma once
// A point light's samples at many lit points at once: what sampleLight (lights/light.h,
// lightSampleFrom) and spawnShadowRayInto (geometry/shading_point.h, offsetRayOrigin) compute
// for one point, in lanes, with the same operations in the same order, so that every lane holds
// the same bits as the scalar code (the reference-vs-production tests hold the two together).
// One point at a time, this arithmetic was most of what a lit point's sample set-up cost.
#include <cstddef>
#include <cstdint>

#include "core/rgb.h"
#include "core/vec.h"
#include "geometry/shading_point.h"

namespace glint {

// Per point: the unit direction to the light, the intensity arriving (lightSampleFrom's, with
// the light's falloff), whether the sample can contribute (the light is in front of the shading
// normal and its intensity not black: queueSamples' test), the cosine with the shading normal,
// and the shadow ray's origin and direction (towards the light's position, with tMax
// kShadowRayEnd, as spawnShadowRayInto makes it).
struct PointLightLanes {
  static constexpr int kMaxPoints = 64;
  float wi[3][kMaxPoints];
  float intensity[3][kMaxPoints];
  int32_t contributes[kMaxPoints];  // non-zero where it can
  float o[3][kMaxPoints];
  float d[3][kMaxPoints];
};

// The light's samples are computed this many points at a time.
inline constexpr int kPointLightLanes = 8;

// Points [0, n) (n <= kMaxPoints) seen from a point light at `position` of `intensity` (falling
// off with the inverse square of the distance where `inverseSquare`): point k's surface point
// at firstPoint + k·stride bytes, and its unit shading normal on the viewer's side
// (SurfacePoint::n) at firstNormal + k·stride bytes.
void samplePointLight(const Vec3f& position, const Rgb& intensity, bool inverseSquare,
                      const ShadingPoint* firstPoint, const Vec3f* firstNormal, size_t stride,
                      int n, PointLightLanes& out);

}  // namespace glint
