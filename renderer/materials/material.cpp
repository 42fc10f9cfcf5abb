#include "materials/material.h"

#include <algorithm>

#include "core/uninitialized_array.h"

namespace glint {

Material defaultMaterial(MaterialKind kind) {
  Material m;
  m.kind = kind;
  Surface& s = m.surface;
  if (kind == MaterialKind::Phong) s.kd = ColorTexture::uniform({0.5f, 0.5f, 0.5f});
  if (kind == MaterialKind::Mirror) s.km = ColorTexture::uniform({1, 1, 1});
  s.ka = s.kd;  // every kind: k_a follows k_d unless the scene gives it
  s.ambientFollowsDiffuse = true;
  return m;
}

Rgb albedo(const Material& m, const SurfacePoint& at) {
  if (m.refracts()) return {1, 1, 1};
  return at.kd.isBlack() ? at.km : at.kd;
}

void drawLobeSamples(const Material* const* materials, const SampleKey* const* keys,
                     const int* slot, int depth, int n, LobeSamples* out) {
  // Dimension 0: the glossy mirror's samples; 1: the blurred refraction's.
  constexpr int kMaxRays = 64;
  const uint32_t dims[2] = {dimension(Dim::Gloss, depth), dimension(Dim::Gloss, depth, 1)};
  for (int first = 0; first < n; first += kMaxRays) {
    const int count = std::min(kMaxRays, n - first);
    // Uninitialised: cleared per call, the arrays cost more than the draws they serve.
    UninitializedArray<SamplePattern, kMaxRays> sets[2];
    const SamplePattern* at[2][kMaxRays];
    uint32_t flat[2][kMaxRays];
    int ray[2][kMaxRays];
    int points[2] = {0, 0}, setCount[2] = {0, 0};
    const SampleKey* setKey[2] = {nullptr, nullptr};
    const Sampler* sampler = nullptr;
    for (int i = first; i < first + count; ++i) {
      out[slot[i]] = LobeSamples{};
      const Material* m = materials[i];
      const SampleKey& key = *keys[i];
      sampler = key.sampler;
      const bool draws[2] = {m->surface.glossy(), m->refracts() && m->dielectric.blurs()};
      for (int d = 0; d < 2; ++d) {
        if (!draws[d]) continue;
        // A pattern depends only on the pixel, the half and the dimension: consecutive rays of
        // one pixel half share it.
        const SampleKey* const last = setKey[d];
        if (!last || last->pixelKey != key.pixelKey || last->half != key.half) {
          sets[d][size_t(setCount[d]++)] = key.pattern(dims[d]);
          setKey[d] = &key;
        }
        at[d][points[d]] = &sets[d][size_t(setCount[d] - 1)];
        flat[d][points[d]] = static_cast<uint32_t>(key.index);
        ray[d][points[d]++] = slot[i];
      }
    }
    for (int d = 0; d < 2; ++d) {
      if (points[d] == 0) continue;
      UninitializedArray<Vec2f, kMaxRays> u;
      sampler->get2DAt(at[d], 1, flat[d], points[d], u.data());
      for (int j = 0; j < points[d]; ++j)
        (d == 0 ? out[ray[d][j]].gloss : out[ray[d][j]].blur) = u[j];
    }
  }
}

}  // namespace glint
