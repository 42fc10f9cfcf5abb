// What an AC3D file says of its surfaces' shading (io/ac3d_shading.h), read as Assimp reads the
// file: each SURF line belongs to the last OBJECT line before it.
#include "io/ac3d_shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace glint {
namespace {

Ac3dShading shadingOf(const std::string& text) {
  std::istringstream in(text);
  return readAc3dShading(in);
}

TEST(Ac3dShading, CountsPolygonsByShadingAndTakesTheLargestCreaseOfSmoothObjects) {
  // A world holding two objects: one smooth at crease 30 (two polygons, and a closed line,
  // SURF 0x11, which is no polygon), one flat at crease 80 (not counted as a crease).
  const Ac3dShading s = shadingOf(
      "AC3Db\nOBJECT world\nkids 2\n"
      "OBJECT poly\ncrease 30.000000\nnumsurf 3\nSURF 0x10\nSURF 0x10\nSURF 0x11\nkids 0\n"
      "OBJECT poly\ncrease 80\nnumsurf 1\nSURF 0x00\nkids 0\n");
  EXPECT_EQ(s.smoothSurfaces, 2);
  EXPECT_EQ(s.flatSurfaces, 1);
  EXPECT_EQ(s.creaseDegrees, 30);
  EXPECT_FALSE(s.creasesDiffer);
}

TEST(Ac3dShading, ATriangleStripIsASurfaceAndLinesAreNot) {
  // SURF types: 0 polygon, 1 closed line, 2 line, 4 triangle strip (which Assimp reads).
  const Ac3dShading s =
      shadingOf("AC3Db\nOBJECT poly\nSURF 0x14\nSURF 0x12\nSURF 0x11\nSURF 0x04\nkids 0\n");
  EXPECT_EQ(s.smoothSurfaces, 1);
  EXPECT_EQ(s.flatSurfaces, 1);
}

TEST(Ac3dShading, SmoothObjectsOfDifferentCreasesAreNamedAndTheLargestTaken) {
  // The second object gives no crease line: the default, 45, beside the first's 20.
  const Ac3dShading s = shadingOf(
      "AC3Db\nOBJECT poly\ncrease 20\nSURF 0x30\nkids 1\nOBJECT poly\nSURF 0x10\nkids 0\n");
  EXPECT_EQ(s.smoothSurfaces, 2);
  EXPECT_EQ(s.creaseDegrees, kDefaultAc3dCreaseDegrees);
  EXPECT_TRUE(s.creasesDiffer);
}

TEST(Ac3dShading, ACreaseThatIsNotAnAngleLeavesTheDefault) {
  for (const char* crease : {"crease nan", "crease -5", "crease 1e9", "crease x"}) {
    const Ac3dShading s =
        shadingOf(std::string("AC3Db\nOBJECT poly\n") + crease + "\nSURF 0x10\nkids 0\n");
    EXPECT_EQ(s.creaseDegrees, kDefaultAc3dCreaseDegrees) << crease;
  }
}

// A fan of `n` triangles about the origin in z = 0, each with its own three corners (as
// Assimp's AC3D reader makes them), the i-th tilted by `tilt` radians about its outer edge's
// direction alternately up and down.
struct Fan {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> triangles;
};
Fan fanOf(int n) {
  Fan f;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2 * M_PI * i / n, a1 = 2 * M_PI * (i + 1) / n;
    const auto base = static_cast<uint32_t>(f.positions.size());
    f.positions.push_back({0, 0, 0});
    f.positions.push_back({float(std::cos(a0)), float(std::sin(a0)), 0});
    f.positions.push_back({float(std::cos(a1)), float(std::sin(a1)), 0});
    f.triangles.insert(f.triangles.end(), {base, base + 1, base + 2});
  }
  return f;
}

TEST(Ac3dShading, CreaseNormalsOfAFlatFanAreItsNormalAndACrowdedPointKeepsItsFaces) {
  // 256 triangles meet at the centre: compared pairwise, each centre corner sums 256 equal
  // normals, +z. Past kMaxCornersCompared (256) the centre keeps each face's own normal, also
  // +z here, and is counted, so the work stays bounded (a million would take 10^12 steps).
  for (const int n : {256, 257}) {
    const Fan f = fanOf(n);
    size_t crowded = 99;
    const std::vector<Vec3f> normals = creaseNormals(f.positions, f.triangles, 45, crowded);
    EXPECT_EQ(crowded, n > int(kMaxCornersCompared) ? 1u : 0u) << n;
    for (const Vec3f& v : normals) EXPECT_NEAR(v.z, 1, 1e-6) << n;
  }
}

TEST(Ac3dShading, CreaseNormalsOfASheetsTwoSidesWithinA180DegreeCreaseStayFinite) {
  // One triangle and its reverse on the same corners' positions: within a 180° crease their
  // normals sum to zero; each keeps its own face's instead of a NaN.
  const std::vector<Vec3f> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                        {0, 0, 0}, {0, 1, 0}, {1, 0, 0}};
  const std::vector<uint32_t> triangles = {0, 1, 2, 3, 4, 5};
  size_t crowded = 0;
  const std::vector<Vec3f> n = creaseNormals(positions, triangles, 180, crowded);
  EXPECT_EQ(n[0].z, 1.0f);
  EXPECT_EQ(n[3].z, -1.0f);
}

}  // namespace
}  // namespace glint
