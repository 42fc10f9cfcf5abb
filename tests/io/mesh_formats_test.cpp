// The formats of io/scene_formats.h's table beyond OBJ, PLY and glTF, read through Assimp
// (io/mesh_io.h): a small file of each loads with its known triangles, bounds and materials, a
// Collada file's unit, up axis, cameras and lights arrive as the file means them, and a
// truncated file of each format is refused naming it. Files of Debian's assimp-testmodels are
// used where Glint cannot write a small one here (the binary FBX, 3DS and Milkshape formats);
// without the package those cases skip, saying so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "collada_util.h"
#include "core/error.h"
#include "io/mesh_io.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

size_t triangles(const MeshFile& f) {
  size_t n = 0;
  for (const TriangleMesh& m : f.parts) n += m.indices.size() / 3;
  return n;
}

Bounds3f bounds(const MeshFile& f) {
  Bounds3f b;
  for (const TriangleMesh& m : f.parts)
    for (const Vec3f& p : m.positions) b.extend(p);
  return b;
}

// Skips the calling test, loudly, where assimp-testmodels is not installed.
#define REQUIRE_MODEL(path)                                        \
  if (!fs::exists(path))                                           \
  GTEST_SKIP() << "assimp-testmodels is not installed (" << (path) \
               << " is missing): this format's load is untested here; tools/lib.sh installs it"

TEST(MeshFormats, ColladaTriangleWithItsMaterial) {
  const std::string file = test::writeTemp("tri.dae", test::colladaDocument());
  const MeshFile f = loadMeshFile(file);
  EXPECT_EQ(triangles(f), 1u);
  ASSERT_EQ(f.materials.size(), 1u);
  EXPECT_EQ(f.materials[0].name, "tri.dae:red");
  // <lambert><diffuse><color>0.8 0.1 0.1: Glint's diffuse colour, unchanged.
  const Rgb kd = f.materials[0].surface.kd.constant;
  EXPECT_NEAR(kd.r, 0.8, 1e-6);
  EXPECT_NEAR(kd.g, 0.1, 1e-6);
  EXPECT_NEAR(kd.b, 0.1, 1e-6);
}

TEST(MeshFormats, ColladaUnitAndUpAxisAreApplied) {
  // Z_UP turns to Glint's +y up (Assimp rotates the root node: (x, y, z) -> (x, z, −y)), and
  // <unit meter="0.5"> halves every length: the vertex at z = 2 lands at y = 1.
  test::ColladaParts p;
  p.upAxis = "Z_UP";
  p.unitMeters = "0.5";
  p.positions = "0 0 0  1 0 0  0 0 2";
  const Bounds3f b = bounds(loadMeshFile(test::writeTemp("zup.dae", test::colladaDocument(p))));
  EXPECT_NEAR(b.hi.y, 1, 1e-6);
  EXPECT_NEAR(b.hi.x, 0.5, 1e-6);
  EXPECT_NEAR(b.hi.z - b.lo.z, 0, 1e-6);
}

TEST(MeshFormats, ColladaCameraAndLightArePlaced) {
  const FileSceneInfo info =
      readMeshFileSceneInfo(test::writeTemp("lit.dae", test::colladaDocument()));
  ASSERT_EQ(info.cameras.size(), 1u);
  const FileCamera& c = info.cameras[0];
  EXPECT_EQ(c.name, "view");  // Assimp names a Collada camera by its node
  // The node moves it to z = 5; Collada cameras look down their −z with +y up.
  EXPECT_NEAR(c.eye.z, 5, 1e-9);
  EXPECT_NEAR(c.lookAt.z - c.eye.z, -1, 1e-6);
  EXPECT_NEAR(c.up.y, 1, 1e-6);
  // yfov 30° and aspect 2: Assimp keeps the horizontal angle, 2·atan(2·tan 15°); back to 30°.
  EXPECT_NEAR(c.yfovDegrees, 30, 1e-4);
  EXPECT_EQ(c.aspectRatio, 2);
  ASSERT_EQ(info.lights.size(), 1u);
  const FileLight& l = info.lights[0];
  EXPECT_EQ(l.type, FileLight::Type::Directional);
  // Turned −90° about +x, the light's −z points down.
  EXPECT_NEAR(l.direction.y, -1, 1e-6);
  EXPECT_NEAR(l.direction.z, 0, 1e-6);
  // Collada's colour is its intensity, in the same units as Glint's (no photometric scale).
  EXPECT_FALSE(l.photometric);
  EXPECT_FLOAT_EQ(l.color.g, 0.25f);
}

TEST(MeshFormats, AFileWithoutMeshesHasNoTriangles) {
  // Collada cameras and a light alone: Assimp would stand pyramids at the nodes in place of
  // meshes (its skeleton meshes); Glint asks it not to, and the file has nothing to render.
  std::string doc = test::colladaDocument();
  const size_t node = doc.find("<node id=\"shape\"");
  doc.erase(node, doc.find("</node>", node) + 7 - node);
  const std::string file = test::writeTemp("cameras_only.dae", doc);
  const std::string message = test::meshLoadError("cameras_only.dae", doc);
  EXPECT_NE(message, "(loaded)");
  EXPECT_EQ(readMeshFileSceneInfo(file).cameras.size(), 1u);
}

TEST(MeshFormats, AsciiStl) {
  // Two facets of the unit square in z = 0.
  const std::string stl =
      "solid square\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\n"
      "endfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n"
      "endfacet\nendsolid square\n";
  const MeshFile f = loadMeshFile(test::writeTemp("square.stl", stl));
  EXPECT_EQ(triangles(f), 2u);
  EXPECT_NEAR(bounds(f).hi.x, 1, 1e-6);
  EXPECT_NEAR(bounds(f).hi.y, 1, 1e-6);
  // Cut after its first facet, Assimp read the one triangle without a word; Glint requires
  // the closing endsolid line.
  const std::string cut = stl.substr(0, stl.find("endfacet\n") + 9);
  EXPECT_NE(test::meshLoadError("cut.stl", cut).find("does not end with an endsolid line"),
            std::string::npos);
}

TEST(MeshFormats, AnStlIsShadedFromItsVerticesNotItsFacetNormals) {
  // A facet of no area whose exporter wrote its normal as NaN (as some do): the file was refused
  // whole ("the normal of vertex 3 of mesh 0 is not finite"). STL is flat by definition and its
  // normals restate the winding: they are not read, and the part is shaded flat.
  const std::string stl =
      "solid s\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\n"
      "endfacet\n"
      "facet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 1 1 0\n"
      "endloop\nendfacet\nendsolid s\n";
  const MeshFile f = loadMeshFile(test::writeTemp("nan-normal.stl", stl));
  ASSERT_EQ(f.parts.size(), 1u);
  EXPECT_TRUE(f.parts[0].normals.empty());
  EXPECT_NEAR(bounds(f).hi.x, 1, 1e-6);
}

TEST(MeshFormats, Ac3d) {
  // One triangle (SURF 0x10: a polygon) with its red material.
  const std::string ac =
      "AC3Db\n"
      "MATERIAL \"red\" rgb 1 0 0  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  shi 10  trans 0\n"
      "OBJECT world\nkids 1\nOBJECT poly\nname \"tri\"\nnumvert 3\n0 0 0\n2 0 0\n0 1 0\n"
      "numsurf 1\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
  const MeshFile f = loadMeshFile(test::writeTemp("tri.ac", ac));
  EXPECT_EQ(triangles(f), 1u);
  EXPECT_NEAR(bounds(f).hi.x, 2, 1e-6);
  ASSERT_EQ(f.materials.size(), 1u);
  EXPECT_NEAR(f.materials[0].surface.kd.constant.r, 1, 1e-6);
  EXPECT_NEAR(f.materials[0].surface.kd.constant.g, 0, 1e-6);
  EXPECT_NE(test::meshLoadError("half.ac", ac.substr(0, ac.size() / 2)), "(loaded)");
}

// Two quads meeting along the y axis at a ridge: each leans 10° from +z (their normals 20°
// apart), shaded smooth (SURF 0x10) unless `flags` says otherwise, in an object of `crease`.
std::string ac3dRidge(const char* flags, const std::string& crease) {
  const double s = std::sin(10 * M_PI / 180), c = std::cos(10 * M_PI / 180);
  const auto v = [](double x, double y, double z) {
    return std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  };
  std::string ac =
      "AC3Db\nMATERIAL \"m\" rgb 1 1 1  amb 0 0 0  emis 0 0 0  spec 0 0 0  shi 1  "
      "trans 0\nOBJECT world\nkids 1\nOBJECT poly\n" +
      crease + "numvert 6\n" + v(-c, 0, -s) + v(0, 0, 0) + v(0, 1, 0) + v(-c, 1, -s) + v(c, 0, -s) +
      v(c, 1, -s) + "numsurf 2\n";
  for (const char* refs : {"0 1 2 3", "1 4 5 2"}) {
    ac += std::string("SURF ") + flags + "\nmat 0\nrefs 4\n";
    std::istringstream corners(refs);
    for (int corner; corners >> corner;) ac += std::to_string(corner) + " 0 0\n";
  }
  return ac + "kids 0\n";
}

// The normals of `f`'s vertices on the ridge (x = 0).
std::vector<Vec3f> ridgeNormals(const MeshFile& f) {
  std::vector<Vec3f> out;
  for (const TriangleMesh& part : f.parts)
    for (size_t i = 0; i < part.normals.size(); ++i)
      if (std::abs(part.positions[i].x) < 1e-6f) out.push_back(part.normals[i]);
  return out;
}

TEST(MeshFormats, Ac3dSmoothSurfacesAreSmoothedWithinTheirCreaseAngle) {
  // Assimp's reader gives AC3D files no normals: a model of smooth surfaces rendered faceted.
  // The quads' normals are 20° apart: within a 45° crease their shared vertices take the
  // average, +z (to float rounding); past a 15° crease they keep each face's, 10° either side.
  const MeshFile smooth =
      loadMeshFile(test::writeTemp("ridge45.ac", ac3dRidge("0x10", "crease 45\n")));
  std::vector<Vec3f> n = ridgeNormals(smooth);
  ASSERT_FALSE(n.empty());
  for (const Vec3f& v : n) EXPECT_NEAR(v.z, 1, 1e-5) << v.x << " " << v.y << " " << v.z;
  const MeshFile creased =
      loadMeshFile(test::writeTemp("ridge15.ac", ac3dRidge("0x10", "crease 15\n")));
  n = ridgeNormals(creased);
  ASSERT_FALSE(n.empty());
  for (const Vec3f& v : n) {
    EXPECT_NEAR(std::abs(v.x), std::sin(10 * M_PI / 180), 1e-5);
    EXPECT_NEAR(v.z, std::cos(10 * M_PI / 180), 1e-5);
  }
  // No crease line: 45°, smoothed. Flat surfaces (SURF 0x00, Wuson.ac's) stay flat: no normals.
  n = ridgeNormals(loadMeshFile(test::writeTemp("ridge.ac", ac3dRidge("0x10", ""))));
  ASSERT_FALSE(n.empty());
  EXPECT_NEAR(n[0].z, 1, 1e-5);
  const MeshFile flat = loadMeshFile(test::writeTemp("flat.ac", ac3dRidge("0x00", "crease 45\n")));
  ASSERT_EQ(flat.parts.size(), 1u);
  EXPECT_TRUE(flat.parts[0].normals.empty());
}

TEST(MeshFormats, X3d) {
  // One IndexedFaceSet quad (split in two triangles), blue.
  const std::string x3d =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Interchange\" "
      "version=\"3.3\"><Scene><Shape><Appearance><Material diffuseColor=\"0 0 1\"/>"
      "</Appearance><IndexedFaceSet coordIndex=\"0 1 2 3 -1\"><Coordinate point=\"0 0 0 3 0 0 "
      "3 1 0 0 1 0\"/></IndexedFaceSet></Shape></Scene></X3D>\n";
  const MeshFile f = loadMeshFile(test::writeTemp("quad.x3d", x3d));
  EXPECT_EQ(triangles(f), 2u);
  EXPECT_NEAR(bounds(f).hi.x, 3, 1e-6);
  EXPECT_NE(test::meshLoadError("half.x3d", x3d.substr(0, x3d.size() / 2)), "(loaded)");
}

TEST(MeshFormats, WusonHasItsTrianglesInEveryFormat) {
  // assimp-testmodels' Wuson is one model saved in many formats: 3732 triangles in each (its
  // OBJ and OFF copies have as many).
  for (const char* name : {"STL/Wuson.stl", "AC/Wuson.ac", "MS3D/Wuson.ms3d"}) {
    REQUIRE_MODEL(kModels / name);
    EXPECT_EQ(triangles(loadMeshFile((kModels / name).string())), 3732u) << name;
  }
}

TEST(MeshFormats, FbxAnd3dsBoxes) {
  // Boxes: 6 faces of 2 triangles; the 3DS one a cube, as wide as it is high and deep.
  REQUIRE_MODEL(kModels / "FBX/box.fbx");
  EXPECT_EQ(triangles(loadMeshFile((kModels / "FBX/box.fbx").string())), 12u);
  const fs::path cube = kModels / "3DS/cube_with_diffuse_texture.3DS";
  REQUIRE_MODEL(cube);
  const MeshFile f = loadMeshFile(cube.string());
  EXPECT_EQ(triangles(f), 12u);
  const Vec3f size = bounds(f).hi - bounds(f).lo;
  EXPECT_NEAR(size.x, size.y, 1e-4 * size.x);
  EXPECT_NEAR(size.x, size.z, 1e-4 * size.x);
}

TEST(MeshFormats, TruncatedBinaryFilesAreRefusedNamingThem) {
  for (const char* name : {"FBX/box.fbx", "3DS/cube_with_diffuse_texture.3DS",
                           "MS3D/twospheres.ms3d", "STL/Spider_binary.stl", "Collada/duck.dae"}) {
    REQUIRE_MODEL(kModels / name);
    std::ifstream in(kModels / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string ext = fs::path(name).extension().string();
    EXPECT_NE(test::meshLoadError("truncated" + ext, bytes.substr(0, bytes.size() / 2)), "(loaded)")
        << name;
  }
}

}  // namespace
}  // namespace glint
