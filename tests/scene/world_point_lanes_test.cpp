// The world's common hits (static flat meshes, static spheres, planes) rebuilt in SSE lanes
// (Scene::worldPointInLanes) against the one-at-a-time code every other hit takes
// (trianglePoint, spherePoint, projectOntoPlane in scene/scene.cpp).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "scene/scene.h"

namespace glint {

// Scene's two paths for a world hit (a friend of Scene).
struct WorldPointPaths {
  static bool inLanes(const Scene& scene, const Ray& ray, const Hit& hit, ShadingPoint& sp) {
    return scene.worldPointInLanes(ray, hit, sp);
  }
  static void oneAtATime(const Scene& scene, const Ray& ray, const Hit& hit, ShadingPoint& sp) {
    scene.shadingPoint<false>(ray, hit, nullptr, sp);
  }
};

namespace {

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool sameBits(const Vec3f& a, const Vec3f& b) {
  return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

constexpr int kTriangles = 64, kSpheres = 16, kPlanes = 8;

// Random shapes at scales from a hundredth to a thousand (the rounding the error bounds follow
// depends on the magnitudes), and rays aimed at them from all around.
struct RandomWorld {
  std::mt19937 rng{20261129};
  std::uniform_real_distribution<float> unit{-1, 1}, positive{0, 1};
  std::uniform_int_distribution<int> exponent{-2, 3};
  Scene scene;

  float scale() { return std::pow(10.0f, float(exponent(rng))); }
  Vec3f inCube(float s) { return s * Vec3f{unit(rng), unit(rng), unit(rng)}; }
  Vec3f direction() {
    for (;;) {
      const Vec3f d = inCube(1);
      if (length(d) > 0.1f) return normalize(d);
    }
  }

  RandomWorld() {
    scene.groups.resize(1);
    TriangleMesh mesh;
    for (int i = 0; i < kTriangles; ++i) {
      const float s = scale();
      const Vec3f corner = inCube(s);
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(k == 0 ? corner : corner + inCube(s));
        mesh.indices.push_back(uint32_t(3 * i + k));
      }
    }
    scene.meshes.push_back(std::move(mesh));
    add(GeomKind::Mesh, 0);
    for (int i = 0; i < kSpheres; ++i) {
      const float s = scale();
      scene.spheres.push_back({inCube(s), s * (0.05f + positive(rng))});
      scene.sphereCenterKeys.emplace_back();
      add(GeomKind::Sphere, uint32_t(i));
    }
    for (int i = 0; i < kPlanes; ++i) {
      scene.planes.push_back({inCube(scale()), direction()});
      scene.planeGeometries.push_back(uint32_t(scene.groups[0].geometries.size()));
      add(GeomKind::Plane, uint32_t(i));
    }
  }
  void add(GeomKind kind, uint32_t index) {
    const uint32_t id = uint32_t(scene.groups[0].geometries.size());
    scene.groups[0].geometries.push_back({kind, index, 100 + id, 200 + id});
  }

  // A ray from a random point around `target`, aimed at it.
  Ray rayTowards(const Vec3f& target, float s) {
    Ray ray;
    ray.o = target + inCube(4 * s);
    ray.d = normalize(target - ray.o);
    ray.time = positive(rng);
    return ray;
  }
};

// Both paths on one hit: the lanes must take it and give every field the other gives, bit for
// bit (an image must not depend on which path a hit took).
void expectSamePoint(const Scene& scene, const Ray& ray, const Hit& hit, const char* what) {
  ShadingPoint lanes, expected;
  ASSERT_TRUE(WorldPointPaths::inLanes(scene, ray, hit, lanes)) << what;
  WorldPointPaths::oneAtATime(scene, ray, hit, expected);
  EXPECT_TRUE(sameBits(lanes.p, expected.p)) << what << " p";
  EXPECT_TRUE(sameBits(lanes.pError, expected.pError)) << what << " pError";
  EXPECT_TRUE(sameBits(lanes.ng, expected.ng)) << what << " ng";
  EXPECT_TRUE(sameBits(lanes.ns, expected.ns)) << what << " ns";
  EXPECT_TRUE(sameBits(lanes.t, expected.t)) << what << " t";
  EXPECT_EQ(lanes.lifted, expected.lifted) << what;
  EXPECT_EQ(lanes.materialId, expected.materialId) << what;
  EXPECT_EQ(lanes.objectId, expected.objectId) << what;
}

TEST(WorldPointInLanes, EqualsTheOneAtATimePointsBitForBit) {
  RandomWorld world;
  const Scene& scene = world.scene;
  const TriangleMesh& mesh = scene.meshes[0];
  int meshHits = 0, sphereHits = 0, planeHits = 0;
  std::uniform_int_distribution<int> triangle(0, kTriangles - 1), sphere(0, kSpheres - 1),
      plane(0, kPlanes - 1);
  for (int i = 0; i < 4000; ++i) {
    {  // a triangle, at a random point inside it (Embree's barycentrics from the watertight test)
      const int tri = triangle(world.rng);
      const Vec3f& p0 = mesh.positions[3 * size_t(tri)];
      const Vec3f &p1 = mesh.positions[3 * size_t(tri) + 1],
                  &p2 = mesh.positions[3 * size_t(tri) + 2];
      const float a = world.positive(world.rng), b = world.positive(world.rng) * (1 - a);
      const Vec3f target = (1 - a - b) * p0 + a * p1 + b * p2;
      const Ray ray = world.rayTowards(target, length(p1 - p0) + length(p2 - p0));
      Hit hit;
      hit.t = intersectTriangle(p0, p1, p2, ray, hit.u, hit.v);
      hit.geomId = 0;
      hit.primId = uint32_t(tri);
      if (hit.t < ray.tMax) {
        expectSamePoint(scene, ray, hit, "triangle");
        ++meshHits;
      }
    }
    {  // a sphere, from outside or inside
      const int k = sphere(world.rng);
      const Sphere& s = scene.spheres[size_t(k)];
      const Ray ray = world.rayTowards(s.center + s.radius * world.inCube(1.2f), s.radius);
      Hit hit;
      hit.t = intersectSphere(s, ray);
      hit.geomId = uint32_t(1 + k);
      if (hit.t < ray.tMax) {
        expectSamePoint(scene, ray, hit, "sphere");
        ++sphereHits;
      }
    }
    {  // a plane, from either side at any angle
      const int k = plane(world.rng);
      const Plane& pl = scene.planes[size_t(k)];
      const float s = world.scale();
      Ray ray;
      ray.o = pl.point + world.inCube(s);
      ray.d = world.direction();
      Hit hit;
      hit.t = intersectPlane(pl, ray);
      hit.geomId = uint32_t(1 + kSpheres + k);
      if (hit.t < ray.tMax) {
        expectSamePoint(scene, ray, hit, "plane");
        ++planeHits;
      }
    }
    if (HasFailure()) return;
  }
  // Each kind was exercised: most rays aimed inside a triangle hit it (a few graze past a thin
  // one); a sphere's rays aim anywhere within 1.2 radii of its centre on each axis, and more
  // than half hit; about half the planes' rays leave away from the plane.
  EXPECT_GT(meshHits, 3000);
  EXPECT_GT(sphereHits, 2000);
  EXPECT_GT(planeHits, 1500);
}

TEST(WorldPointInLanes, LeavesMovingAndSmoothSurfacesToTheGeneralPath) {
  // A moving sphere's centre and a smooth mesh's normals are not in the lanes: they answer
  // false, so that shadingPoint takes the general path.
  RandomWorld world;
  Scene& scene = world.scene;
  ShadingPoint sp;
  Hit hit;
  hit.t = 1;
  hit.geomId = 1;  // sphere 0
  scene.sphereCenterKeys[0] = {scene.spheres[0].center, scene.spheres[0].center + Vec3f{1, 0, 0}};
  EXPECT_FALSE(WorldPointPaths::inLanes(scene, world.rayTowards({0, 0, 0}, 1), hit, sp));
  hit.geomId = 0;  // the mesh, given vertex normals
  hit.primId = 0;
  scene.meshes[0].normals.assign(scene.meshes[0].positions.size(), Vec3f{0, 0, 1});
  EXPECT_FALSE(WorldPointPaths::inLanes(scene, world.rayTowards({0, 0, 0}, 1), hit, sp));
}

TEST(WorldPointInLanes, TrianglesOfAnySizeGetAUnitNormal) {
  // A triangle of edges 6·10^9 (a ground plane modelled in millimetres of a city) has an edge
  // cross product whose square passes float's range: its normal was normalised to (0, 0, 0)
  // and the surface rendered black. Edges of 10^-12 square below float's normal range. Both
  // leave the lanes (false) for the general path, which scales the normal before normalising
  // it; a triangle of ordinary size keeps normalize's bits. 10^18 is as far as Embree takes
  // coordinates (core/ray.h); 10^-20 gives a subnormal cross product.
  for (const float size : {3e9f, 1e18f, 1e-12f, 1e-20f, 1.0f}) {
    Scene scene;
    scene.groups.resize(1);
    TriangleMesh mesh;
    mesh.positions = {{-size, -size, -1}, {size, -size, -1}, {0, size, -1}};
    mesh.indices = {0, 1, 2};
    scene.meshes.push_back(std::move(mesh));
    scene.groups[0].geometries.push_back({GeomKind::Mesh, 0, 0, 0});
    Ray ray;
    ray.o = {0, 0, 4};
    ray.d = {0, 0, -1};
    Hit hit;
    hit.t = 5;
    hit.u = hit.v = 1.0f / 3;
    hit.geomId = 0;
    hit.primId = 0;
    ShadingPoint lanes, general;
    const bool inLanes = WorldPointPaths::inLanes(scene, ray, hit, lanes);
    EXPECT_EQ(inLanes, size == 1.0f) << size;
    WorldPointPaths::oneAtATime(scene, ray, hit, general);
    EXPECT_TRUE(sameBits(general.ng, Vec3f{0, 0, 1}))
        << size << ": " << general.ng.x << " " << general.ng.y << " " << general.ng.z;
    if (inLanes) {
      EXPECT_TRUE(sameBits(lanes.ng, general.ng));
    }
  }
  // normalizeAnyScale itself: normalize's bits in float's range, a unit vector beyond it, and
  // what normalize gives for zero and non-finite vectors.
  const Vec3f ordinary{0.3f, -4, 12};
  EXPECT_TRUE(sameBits(normalizeAnyScale(ordinary), normalize(ordinary)));
  for (const float s : {1e20f, 1e-25f, 1e37f, 1e-44f}) {
    const Vec3f n = normalizeAnyScale(s * Vec3f{3, 4, 0});
    EXPECT_NEAR(n.x, 0.6f, 1e-7f) << s;
    EXPECT_NEAR(n.y, 0.8f, 1e-7f) << s;
  }
  EXPECT_TRUE(std::isnan(normalizeAnyScale(Vec3f{0, 0, 0}).x));
}

}  // namespace
}  // namespace glint
