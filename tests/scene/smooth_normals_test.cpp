// Smooth shading: a mesh's vertex normals are interpolated across each triangle
// (Scene::smoothNormal); secondary rays leave from the geometric surface, shadow rays from the
// point lifted towards the smooth surface (geometry/terminator.h).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "accel/accelerator.h"
#include "oracle_util.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A UV sphere of radius 1 at the origin, `rings` × `segments`, as an inline mesh object; with
// `normals`, each vertex carries the exact sphere normal (its position).
std::string uvSphereMesh(int rings, int segments, bool normals) {
  std::ostringstream pos, idx;
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
  return mesh + "}";
}

std::string uvSphere(int rings, int segments, bool normals) {
  return R"({"render": {"width": 8, "height": 8},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}}, "lights": [],
    "objects": [)" +
         uvSphereMesh(rings, segments, normals) + "]}";
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

// The shadow terminator (Hanika, Ray Tracing Gems II ch. 4): a coarse sphere with exact vertex
// normals, lit from the side, against the analytic sphere it stands for. Shadow rays from the
// flat facets hit the neighbouring facets along the terminator, cutting the shading off in
// blocks; from the point lifted towards the smooth surface they do not. Compared where both
// images are covered (alpha 1): the polygon's outline differs from the circle's by the facets'
// chord error, which no shading can mend.
// The RGBA pixels of `object` lit from the side, after checking that the reference integrator
// renders the same image.
std::vector<float> renderLitSphere(const std::string& object) {
  const Scene scene = test::sceneFromText(
      R"({"render": {"width": 96, "height": 96, "spp": 4, "transparent_background": true},
      "camera": {"eye": [0,0,4], "look_at": [0,0,0], "vfov": 35},
      "materials": {"m": {"type": "phong", "kd": [0.8,0.8,0.8], "ka": [0,0,0]}},
      "lights": [{"type": "directional", "direction": [-1,-0.3,-0.35], "intensity": [1,1,1]}],
      "objects": [)" +
      object + "]}");
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  const RenderResult result = renderScene(scene, *accel, opt);
  EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, opt, result, object.substr(0, 40)), 0);
  return result.film.toFloatRgba();
}

// RMSE over RGB of the pixels both images cover whole.
double coveredRmse(const std::vector<float>& a, const std::vector<float>& b, int* covered) {
  double sum = 0;
  *covered = 0;
  for (size_t p = 0; p + 3 < a.size(); p += 4) {
    if (a[p + 3] != 1 || b[p + 3] != 1) continue;
    ++*covered;
    for (int c = 0; c < 3; ++c) sum += std::pow(double(a[p + c]) - b[p + c], 2);
  }
  return std::sqrt(sum / std::max(1, 3 * *covered));
}

// Pixels that `truth` shows lit (red above 0.08: kd 0.8 at a cosine above 0.1) and `image`
// shows in shadow (below 0.01): the blocks cut out of a terminator.
int litPixelsShadowed(const std::vector<float>& truth, const std::vector<float>& image) {
  int count = 0;
  for (size_t p = 0; p + 3 < truth.size(); p += 4)
    if (truth[p + 3] == 1 && image[p + 3] == 1 && truth[p] > 0.08f && image[p] < 0.01f) ++count;
  return count;
}

TEST(SmoothNormals, CoarseSmoothSphereShadesLikeTheAnalyticOneAtItsTerminator) {
  const std::string sphere =
      R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"})";
  const std::vector<float> analytic = renderLitSphere(sphere);
  const std::vector<float> smooth = renderLitSphere(uvSphereMesh(8, 16, true));
  const std::vector<float> faceted = renderLitSphere(uvSphereMesh(8, 16, false));
  int coveredSmooth = 0, coveredFaceted = 0;
  const double smoothError = coveredRmse(analytic, smooth, &coveredSmooth);
  const double facetedError = coveredRmse(analytic, faceted, &coveredFaceted);
  ASSERT_GT(coveredSmooth, 2000);  // the sphere spans about 3 600 of the 9 216 pixels
  EXPECT_EQ(coveredSmooth, coveredFaceted);
  // No lit pixel is cut out of the terminator (shadow rays from the facets themselves cut out a
  // few dozen here), and the whole is within half the faceted mesh's error.
  EXPECT_EQ(litPixelsShadowed(analytic, smooth), 0);
  EXPECT_LT(smoothError, 0.5 * facetedError);
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
