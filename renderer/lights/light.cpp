#include "lights/light.h"

#include "core/frame.h"

namespace glint {

QuadLight::QuadLight(const Vec3f& corner, const Vec3f& edge1, const Vec3f& edge2)
    : corner_(corner), edge1_(edge1), edge2_(edge2) {
  const Vec3f n = cross(edge1, edge2);
  area_ = length(n);
  // Edges past about 10^9.5 square |n| past float's range: scaled first, as normalizeAnyScale
  // does for the normal (which is n / |n|, normalize's bits, in range).
  if (const float largest = maxComponent(abs(n)); !(area_ < kInfinity) && largest < kInfinity)
    area_ = largest * length(Vec3f{n.x / largest, n.y / largest, n.z / largest});
  normal_ = normalizeAnyScale(n);
}

DiskLight::DiskLight(const Vec3f& center, const Vec3f& normal, float radius)
    : center_(center), normal_(normal), radius_(radius), area_(kPi * radius * radius) {
  Vec3f t, b;
  orthonormalBasis(normal, t, b);
  axisX_ = radius * t;
  axisY_ = radius * b;
}

int lightSampleCount(const Light& light) {
  if (const auto* q = std::get_if<QuadLight>(&light)) return q->samples;
  if (const auto* d = std::get_if<DiskLight>(&light)) return d->samples;
  if (const auto* e = std::get_if<EnvironmentLight>(&light)) return e->samples;
  return 1;
}

}  // namespace glint
