#include "app/procedural_scene.h"

#include <cmath>

namespace glint {

Scene makeProceduralScene(size_t triangles) {
  Scene s;
  s.sourcePath = "<procedural " + std::to_string(triangles) + " triangles>";
  s.render.width = 640;
  s.render.height = 360;
  s.render.spp = 1;
  s.render.ambient = {0.1f, 0.1f, 0.1f};
  s.render.background = {0.6f, 0.7f, 0.9f};
  s.cameraDesc.eye = {0, 6, 14};
  s.cameraDesc.lookAt = {0, 0, 0};
  s.cameraDesc.vfovDegrees = 45;
  Material ground = defaultMaterial(MaterialKind::Phong);
  ground.name = "ground";
  ground.surface.kd = ground.surface.ka = ColorTexture::uniform({0.5f, 0.6f, 0.4f});
  s.materials.push_back(ground);
  s.lights.push_back(PointLight{{5, 12, 8}, {1, 1, 1}, Falloff::None});

  // n × n cells of two triangles each over [−10, 10]².
  const auto n = static_cast<uint32_t>(std::max(1.0, std::sqrt(double(triangles) / 2)));
  TriangleMesh m;
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) {
      const float x = -10 + 20 * float(i) / float(n), z = -10 + 20 * float(j) / float(n);
      const float y = 0.6f * std::sin(0.9f * x) * std::cos(0.7f * z) +
                      0.15f * std::sin(4.1f * x + 2.3f * z) + 0.05f * std::sin(13 * x - 11 * z);
      m.positions.push_back({x, y, z});
    }
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  m.padForEmbree();
  s.meshes.push_back(std::move(m));
  s.spheres.push_back({{0, 2, 0}, 1.5f});
  s.sphereCenterKeys.emplace_back();
  s.groups.push_back({"", {{GeomKind::Mesh, 0, 0, 0}, {GeomKind::Sphere, 0, 0, 1}}});
  s.features = computeFeatures(s);
  return s;
}

}  // namespace glint
