#include "materials/normal_map.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"

namespace glint {

namespace {

// The smallest cosine a mapped normal keeps with the geometric normal: a map that bends it to
// the horizon or past it (a steep bump, a scale of 10) is held just above the surface.
constexpr float kMinCosToGeometric = 1.0f / 64;

Vec3f unitOr(const Vec3f& v, const Vec3f& otherwise) {
  const float len = length(v);
  return len > 0 && std::isfinite(len) ? v / len : otherwise;
}

// The normal map's normal in the frame of unit n: the tangent sp.tangent made orthogonal to n
// (or any tangent, where it is parallel to n or missing), the bitangent on the side of +v.
Vec3f normalMapped(const NormalMap& map, const ShadingPoint& sp, const Vec3f& n, const Vec3f& wo,
                   float footprint) {
  const Rgb c = map.image->data(imageFootprint(sp, wo, footprint, map.uvTransform));
  const Vec3f m{(2 * c.r - 1) * map.scale, (2 * c.g - 1) * map.scale, 2 * c.b - 1};
  Vec3f t = sp.tangent - dot(sp.tangent, n) * n, b;
  const float len = length(t);
  if (len > 1e-6f && std::isfinite(len)) {
    t = t / len;
    b = sp.tangentSign * cross(n, t);
  } else {
    orthonormalBasis(n, t, b);
  }
  return unitOr(m.x * t + m.y * b + m.z * n, n);
}

// The bump map's normal for the surface whose normal is unit n: the height's derivatives along
// the image's s and t by central differences over half the footprint (at least 1e-4 of the
// image), carried to (u, v) through the texture transform (t = 1 − v').
Vec3f bumped(const BumpMap& map, const ShadingPoint& sp, const Vec3f& n, const Vec3f& wo,
             float footprint) {
  const ImageFootprint at = imageFootprint(sp, wo, footprint, map.uvTransform);
  const float hs = std::max(0.5f * (std::fabs(at.axisA.x) + std::fabs(at.axisB.x)), 1e-4f);
  const float ht = std::max(0.5f * (std::fabs(at.axisA.y) + std::fabs(at.axisB.y)), 1e-4f);
  const auto height = [&](float ds, float dt) {
    return map.image->data({{at.st.x + ds, at.st.y + dt}, at.axisA, at.axisB}).r;
  };
  const float dhds = map.scale * (height(hs, 0) - height(-hs, 0)) / (2 * hs);
  const float dhdt = map.scale * (height(0, ht) - height(0, -ht)) / (2 * ht);
  const UvTransform& x = map.uvTransform;
  const float dhdu = dhds * x.m00 - dhdt * x.m10, dhdv = dhds * x.m01 - dhdt * x.m11;
  // The surface's tangents in the plane of n (a smooth or normal-mapped n leans from dp/du ×
  // dp/dv), then displaced along it.
  const Vec3f pu = sp.dpdu - dot(sp.dpdu, n) * n, pv = sp.dpdv - dot(sp.dpdv, n) * n;
  const Vec3f bumpedNormal = cross(pu + dhdu * n, pv + dhdv * n);
  return unitOr(dot(bumpedNormal, n) < 0 ? -bumpedNormal : bumpedNormal, n);
}

}  // namespace

Vec3f mappedNormal(const ShadingMaps& maps, const ShadingPoint& sp, const Vec3f& wo,
                   float footprint) {
  Vec3f n = sp.ns;
  if (maps.normal.image) n = normalMapped(maps.normal, sp, n, wo, footprint);
  if (maps.bump.image) n = bumped(maps.bump, sp, n, wo, footprint);
  // On the geometric normal's side, as sp.ns is (ShadingPoint::shadingNormalFacing): a normal
  // past the limit is turned towards ng, in the plane of the two, until its cosine is the
  // limit's.
  const float cosToGeometric = dot(n, sp.ng);
  if (!(cosToGeometric < kMinCosToGeometric)) return n;
  const Vec3f across = n - cosToGeometric * sp.ng;
  const float len = length(across);
  if (!(len > 0 && std::isfinite(len))) return sp.ng;
  return across * (std::sqrt(1 - kMinCosToGeometric * kMinCosToGeometric) / len) +
         kMinCosToGeometric * sp.ng;
}

}  // namespace glint
