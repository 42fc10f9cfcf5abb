#include "materials/texture.h"

#include <algorithm>
#include <cmath>

#include "materials/procedural.h"

namespace glint {

Rgb ColorTexture::patternAt(const TextureLookup& at) const {
  if (pattern == TexturePattern::VertexColor) return constant * at.sp.vertexColor;
  if (pattern == TexturePattern::Image) {
    const Rgb c = constant * image->color(imageFootprint(at.sp, at.wo, at.footprint, uvTransform));
    return timesVertexColor ? c * at.sp.vertexColor : c;
  }
  // World space, one unit per feature (divided, not multiplied by 1/scale: the checker's cells
  // stay where they were before the other patterns came).
  const Vec3d world = toDouble(at.sp.p) + at.worldOrigin;
  const Vec3d p{world.x / scale, world.y / scale, world.z / scale};
  float w = 0;
  switch (pattern) {
    case TexturePattern::Checker:
      // Exactly a or b: no blend that rounding could make differ from the colour given.
      return checkerPattern(p) > 0 ? b : a;
    case TexturePattern::Noise:
      w = noisePattern(p);
      break;
    case TexturePattern::Marble:
      w = marblePattern(p);
      break;
    case TexturePattern::Wood:
      w = woodPattern(p);
      break;
    default:
      break;
  }
  return a * (1 - w) + b * w;
}

ImageFootprint imageFootprint(const ShadingPoint& sp, const Vec3f& wo, float width,
                              const UvTransform& transform) {
  ImageFootprint f;
  const bool second = transform.uvSet == 1;
  const Vec2f uv = transform.point(second ? sp.uv1 : sp.uv);
  f.st = {uv.x, 1 - uv.y};
  f.wrapS = transform.wrapS;
  f.wrapT = transform.wrapT;
  // The footprint's axes on the surface: across the ray (length `width`), and along the ray's
  // trace on the surface, stretched by 1/cos θ (capped: at grazing angles OpenImageIO caps the
  // anisotropy anyway).
  const Vec3f n = sp.ng;
  const float cosTheta = std::fabs(dot(wo, n));
  Vec3f across = cross(n, wo);
  const float acrossLength = length(across);
  if (!(acrossLength > 1e-6f)) {  // seen head on: any tangent
    across = std::fabs(n.x) < 0.9f ? cross(n, Vec3f{1, 0, 0}) : cross(n, Vec3f{0, 1, 0});
    across = normalize(across);
  } else {
    across = across / acrossLength;
  }
  const Vec3f along = cross(across, n);
  const Vec3f axisA = across * width;
  const Vec3f axisB = along * (width / std::max(cosTheta, 1.0f / 32));
  // Solve du·dpdu + dv·dpdv = axis in the least-squares sense (the tangents need not be
  // orthogonal): the 2×2 normal equations.
  const Vec3f& dpdu = second ? sp.dpdu1 : sp.dpdu;
  const Vec3f& dpdv = second ? sp.dpdv1 : sp.dpdv;
  const float a = dot(dpdu, dpdu), b = dot(dpdu, dpdv), c = dot(dpdv, dpdv);
  const float det = a * c - b * b;
  const auto toUv = [&](const Vec3f& axis) -> Vec2f {
    if (!(std::fabs(det) > 1e-20f)) return {0, 0};  // no tangents: filtered as a point
    const float pu = dot(dpdu, axis), pv = dot(dpdv, axis);
    const Vec2f d = transform.vector({(c * pu - b * pv) / det, (a * pv - b * pu) / det});
    return {d.x, -d.y};
  };
  f.axisA = toUv(axisA);
  f.axisB = toUv(axisB);
  return f;
}

}  // namespace glint
