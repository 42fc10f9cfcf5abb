// Smooth shading (issue 23): a mesh's vertex normals are interpolated across each triangle
// (Scene::smoothNormal), while secondary rays still leave from the geometric surface.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "accel/accelerator.h"
#include "test_util.h"

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A UV sphere of radius 1 at the origin, `rings` × `segments`, as an inline mesh; with
// `normals`, each vertex carries the exact sphere normal (its position).
std::string uvSphere(int rings, int segments, bool normals) {
  std::ostringstream pos, nrm, idx;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = kPi * r / rings, phi = 2 * kPi * s / segments;
      const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta),
                   z = std::sin(theta) * std::sin(phi);
      pos << (r || s ? "," : "") << "[" << x << "," << y << "," << z << "]";
    }
  const int row = segments + 1;
  bool first = true;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * row + s, b = a + row;
      for (const auto& t : {std::array<int, 3>{a, a + 1, b}, std::array<int, 3>{a + 1, b + 1, b}}) {
        idx << (first ? "" : ",") << "[" << t[0] << "," << t[1] << "," << t[2] << "]";
        first = false;
      }
    }
  std::string mesh = R"({"type": "mesh", "material": "m", "positions": [)" + pos.str() +
                     R"(], "indices": [)" + idx.str() + "]";
  if (normals) mesh += R"(, "normals": [)" + pos.str() + "]";
  mesh += "}";
  return R"({"render": {"width": 8, "height": 8},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "lights": [],
    "objects": [)" +
         mesh + "]}";
}

struct AngleErrors {
  double mean = 0, max = 0;
  int hits = 0;
};

// Angles between the shading normal and the true sphere normal at the hit, over a grid of rays
// from the camera's side towards the sphere.
AngleErrors shadingNormalErrors(const Scene& scene) {
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  AngleErrors e;
  for (int i = 0; i < 41; ++i)
    for (int j = 0; j < 41; ++j) {
      Ray ray;
      ray.o = Vec3f{-0.95f + 0.0475f * float(i), -0.95f + 0.0475f * float(j), 5} -
              toFloat(scene.worldOrigin);
      ray.d = {0, 0, -1};
      const Hit hit = accel->intersect(ray);
      if (!hit) continue;
      const ShadingPoint sp = scene.shadingPoint(ray, hit);
      const Vec3f truth = normalize(sp.p + toFloat(scene.worldOrigin));
      const double angle = std::acos(std::min(1.0f, dot(sp.ns, truth)));
      e.mean += angle;
      e.max = std::max(e.max, angle);
      ++e.hits;
    }
  e.mean /= std::max(1, e.hits);
  return e;
}

TEST(SmoothNormals, InterpolatedNormalsFollowTheAnalyticSphere) {
  // 24 rings x 48 segments: neighbouring vertices are θ = 7.5° apart. A flat facet's normal is
  // off the sphere's by up to about θ/√2 (5.3°) at its corners. Normalised linear interpolation
  // of exact vertex normals errs by O(θ²): at most the sag of an edge's midpoint, θ²/8 (0.12°).
  // Measured: smooth at most 0.04°; flat 2.7° on average and 5.3° at worst.
  const double theta = 7.5 * kPi / 180;
  const AngleErrors smooth = shadingNormalErrors(test::sceneFromText(uvSphere(24, 48, true)));
  const AngleErrors flat = shadingNormalErrors(test::sceneFromText(uvSphere(24, 48, false)));
  ASSERT_GT(smooth.hits, 1000);
  EXPECT_EQ(smooth.hits, flat.hits);
  EXPECT_LT(smooth.max, theta * theta / 8);
  // The same rays see the facets of the flat mesh: the comparison is not vacuous.
  EXPECT_GT(flat.max, 0.9 * theta / std::sqrt(2.0));
}

TEST(SmoothNormals, TheShadingNormalStaysOnTheGeometricNormalsSide) {
  // Vertex normals that lean far from a flat triangle (z = 0, ng = +z): each is 80° off +z. At
  // every hit the shading normal is on ng's side, and the spawned ray leaves from the
  // geometric surface, not along the shading normal.
  const Scene scene = test::sceneFromText(R"({"render": {"width": 8, "height": 8},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "lights": [],
    "objects": [{"type": "mesh", "material": "m",
      "positions": [[-1,-1,0],[1,-1,0],[0,1,0]], "indices": [[0,1,2]],
      "normals": [[0.98,0,0.17],[-0.98,0,0.17],[0,-0.98,0.17]]}]})");
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  Ray ray;
  ray.o = Vec3f{0.1f, -0.2f, 5} - toFloat(scene.worldOrigin);
  ray.d = {0, 0, -1};
  const Hit hit = accel->intersect(ray);
  ASSERT_TRUE(hit);
  const ShadingPoint sp = scene.shadingPoint(ray, hit);
  EXPECT_GT(dot(sp.ns, sp.ng), 0.0f);
  EXPECT_NEAR(length(sp.ns), 1.0f, 1e-6f);
  EXPECT_NE(sp.ns.z, sp.ng.z);  // smooth, not flat
  // Facing the viewer (+z side), the shading normal is ns itself; from behind, its opposite.
  EXPECT_EQ(sp.shadingNormalFacing({0, 0, 1}).z, sp.ns.z);
  EXPECT_EQ(sp.shadingNormalFacing({0, 0, -1}).z, -sp.ns.z);
}

TEST(SmoothNormals, NormalsMustMatchThePositionsAndFilesKeepTheirOwn) {
  EXPECT_NE(test::sceneErrorOf(R"({"render": {"width": 8, "height": 8},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "lights": [],
    "objects": [{"type": "mesh", "material": "m",
      "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]],
      "normals": [[0,0,1],[0,0,1]]}]})")
                .find("objects[0].normals: has 2 normals; the mesh has 3 positions"),
            std::string::npos);
}

}  // namespace
}  // namespace glint
