// intersectLanes against intersectSphere and intersectQuad, lane by lane and bit for bit, at
// every vector width this CPU runs: a render must not depend on which rays Embree put in one
// packet.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/hash.h"
#include "geometry/shape_lanes.h"

namespace glint {
namespace {

// A packet in Embree's layout, built from rays.
struct Packet {
  std::vector<float> o[3], d[3], tMin, tMax;
  std::vector<int> valid;

  void add(const Ray& r, bool isValid) {
    for (int k = 0; k < 3; ++k) o[k].push_back(r.o[k]), d[k].push_back(r.d[k]);
    tMin.push_back(r.tMin);
    tMax.push_back(r.tMax);
    valid.push_back(isValid ? -1 : 0);
  }
  RayLanes lanes() const {
    return {{o[0].data(), o[1].data(), o[2].data()},
            {d[0].data(), d[1].data(), d[2].data()},
            tMin.data(),
            tMax.data(),
            valid.data()};
  }
  Ray ray(size_t i) const {
    Ray r;
    r.o = {o[0][i], o[1][i], o[2][i]};
    r.d = {d[0][i], d[1][i], d[2][i]};
    r.tMin = tMin[i];
    r.tMax = tMax[i];
    return r;
  }
};

const Sphere kSphere{{0.25f, -0.5f, 1.0f}, 0.75f};

// Rays of every kind the kernel branches on, by index: aimed at random points near the sphere
// (hits from outside, misses, grazing), from inside it, from its surface through its centre
// and along its tangent (q = 0 in intersectSphere), cut short by tMax before the sphere or started
// past it by tMin, and invalid lanes holding NaN and infinities (Embree leaves whatever it likes
// there).
Ray caseRay(int i, bool& valid) {
  auto u = [&](int k) { return toUnitFloat(hashKey(11, static_cast<uint32_t>(i), k)); };
  const Vec3f c = kSphere.center;
  const float r = kSphere.radius;
  Ray ray;
  valid = true;
  ray.o = c + Vec3f{8 * u(0) - 4, 8 * u(1) - 4, 3 + u(2)};
  const Vec3f target = c + 1.3f * r * Vec3f{2 * u(3) - 1, 2 * u(4) - 1, 2 * u(5) - 1};
  ray.d = target - ray.o;
  switch (i % 8) {
    case 1:  // from inside
      ray.o = c + 0.5f * r * Vec3f{2 * u(6) - 1, 2 * u(7) - 1, 2 * u(8) - 1};
      break;
    case 2:  // from the surface straight through the centre: hits the far side
      ray.o = c + Vec3f{r, 0, 0};
      ray.d = {-1, 0, 0};
      break;
    case 6:  // from the surface along the tangent
      ray.o = c + Vec3f{r, 0, 0};
      ray.d = {0, 1, 0};
      break;
    case 3:  // stops short
      ray.tMax = 0.5f * u(9);
      break;
    case 4:  // starts late
      ray.tMin = 0.5f + u(10);
      break;
    case 5:  // an ignored lane with garbage in it
      valid = false;
      ray.o = {std::numeric_limits<float>::quiet_NaN(), kInfinity, -kInfinity};
      ray.d = {0, 0, 0};
      break;
    default:
      break;
  }
  return ray;
}

// A quad around the sphere's place, tilted, so that caseRay's rays hit and miss it alike.
const Quad kQuad{{-0.5f, -1.25f, 0.75f}, {1.5f, 0.25f, 0}, {0.125f, 1.5f, 0.5f}};

float scalarTest(const Sphere& s, const Ray& r, float& u, float& v) {
  u = v = 0;
  return intersectSphere(s, r);
}
float scalarTest(const Quad& q, const Ray& r, float& u, float& v) {
  return intersectQuad(q, r, u, v);
}

template <class Shape>
void expectScalarBits(const Shape& shape, const char* name) {
  for (int width : {4, 8, 16}) {
    if (!laneWidthSupported(width)) continue;
    int hits = 0, misses = 0;
    // Packet sizes Embree uses (4, 8, 16) and odd ones, which mix kernels and single lanes.
    for (int n : {16, 8, 4, 13, 5, 1}) {
      for (int packet = 0; packet < 200; ++packet) {
        Packet p;
        for (int l = 0; l < n; ++l) {
          bool valid = true;
          const Ray r = caseRay(packet * kMaxLanes + l + n * 7919, valid);
          p.add(r, valid);
        }
        LaneHits found;
        const uint32_t mask = intersectLanes(shape, p.lanes(), n, found, width);
        const std::string where =
            std::string(name) + ", width " + std::to_string(width) + ", n " + std::to_string(n);
        EXPECT_EQ(mask >> n, 0u) << where;
        for (int l = 0; l < n; ++l) {
          float u = 0, v = 0;
          const float t = scalarTest(shape, p.ray(size_t(l)), u, v);
          const bool hit = p.valid[size_t(l)] != 0 && t < p.tMax[size_t(l)];
          ASSERT_EQ(bool(mask >> l & 1), hit) << where << ", lane " << l;
          if (!hit) {
            ++misses;
            continue;
          }
          ++hits;
          EXPECT_EQ(std::bit_cast<uint32_t>(found.t[l]), std::bit_cast<uint32_t>(t))
              << where << ", lane " << l << ": " << found.t[l] << " vs " << t;
          EXPECT_EQ(std::bit_cast<uint32_t>(found.u[l]), std::bit_cast<uint32_t>(u))
              << where << ", lane " << l;
          EXPECT_EQ(std::bit_cast<uint32_t>(found.v[l]), std::bit_cast<uint32_t>(v))
              << where << ", lane " << l;
        }
      }
    }
    // Both answers exercised at every width (a third or more of the aimed rays hit).
    EXPECT_GT(hits, 1000) << name << ", width " << width;
    EXPECT_GT(misses, 1000) << name << ", width " << width;
  }
  EXPECT_TRUE(laneWidthSupported(4));  // SSE2: four lanes run on every x86-64 CPU
}

TEST(ShapeLanes, SpheresGiveTheScalarBitsLaneByLaneAtEveryWidth) {
  expectScalarBits(kSphere, "sphere");
}

TEST(ShapeLanes, QuadsGiveTheScalarBitsLaneByLaneAtEveryWidth) { expectScalarBits(kQuad, "quad"); }

TEST(ShapeLanes, SphereSurfacePointsLeavingAlongTheTangentOrThroughTheCentre) {
  // From (1, −0.5, 1), on the sphere (every number exact): along the tangent (0, 1, 0) both
  // roots are 0 (intersectSphere's q = 0), not inside (tMin, tMax) = (0, ∞): no hit. Through
  // the centre (−1, 0, 0): the far side, at t = 2r = 1.5 exactly.
  const Vec3f onSurface = kSphere.center + Vec3f{kSphere.radius, 0, 0};
  for (int width : {4, 8, 16}) {
    if (!laneWidthSupported(width)) continue;
    Packet p;
    for (int l = 0; l < width; ++l)
      p.add({onSurface, l % 2 ? Vec3f{-1, 0, 0} : Vec3f{0, 1, 0}}, true);
    LaneHits found;
    const uint32_t mask = intersectLanes(kSphere, p.lanes(), width, found, width);
    for (int l = 0; l < width; ++l) {
      EXPECT_EQ(bool(mask >> l & 1), l % 2 == 1) << "width " << width << ", lane " << l;
      if (l % 2) {
        EXPECT_EQ(found.t[l], 1.5f) << "width " << width << ", lane " << l;
      }
    }
  }
}

}  // namespace
}  // namespace glint
