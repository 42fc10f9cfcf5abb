// Glint's PLY reader (io/ply_reader.h): the same small meshes in ASCII and both binary byte
// orders, polygons fanned, normals and texture coordinates kept, what it skips, and files that
// lie (indices past the vertices, bodies cut short, counts the file cannot hold), each refused
// naming the file and the element. Values are exact: every number here is a small binary
// fraction, so ASCII and binary give the same floats.
#include "io/ply_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "core/log.h"
#include "io/load_progress.h"
#include "io/mesh_io.h"
#include "test_util.h"

namespace glint {
namespace {

// Binary PLY values in either byte order.
struct Body {
  bool bigEndian = false;
  std::string bytes;
  template <class T>
  Body& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof b);
    if (bigEndian) std::reverse(b, b + sizeof b);
    bytes.append(b, sizeof b);
    return *this;
  }
};

// A unit square (0,0,0) (1,0,0) (1,1,0) (0,1,0) as one quad and a triangle (0,1,0) (1,1,0)
// (0.5,1.5,0) above it, with normals (0,0,1) and uvs = (x, y / 2): five vertices, two faces.
const float kXyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 1.5f, 0}};

const char* kAsciiHeader =
    "ply\nformat ascii 1.0\ncomment a quad and a triangle\nelement vertex 5\n"
    "property float x\nproperty float y\nproperty float z\nproperty float nx\n"
    "property float ny\nproperty float nz\nproperty float u\nproperty float v\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n";

std::string asciiQuadAndTriangle() {
  std::string s = kAsciiHeader;
  for (const auto& p : kXyz) {
    char line[128];
    std::snprintf(line, sizeof line, "%g %g %g 0 0 1 %g %g\n", double(p[0]), double(p[1]),
                  double(p[2]), double(p[0]), double(p[1] / 2));
    s += line;
  }
  return s + "4 0 1 2 3\n3 3 2 4\n";
}

// The same mesh in binary, with other types than the ASCII one: double positions, uchar
// normals would not do, so float normals; a ushort count and uint indices; s, t as the uvs.
std::string binaryQuadAndTriangle(bool bigEndian) {
  std::string s = std::string("ply\nformat ") +
                  (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 5\nproperty double x\nproperty double y\n"
                  "property double z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                  "property float s\nproperty float t\nelement face 2\n"
                  "property list ushort uint vertex_index\nend_header\n";
  Body b{bigEndian, {}};
  for (const auto& p : kXyz) {
    b.put(double(p[0])).put(double(p[1])).put(double(p[2]));
    b.put(0.0f).put(0.0f).put(1.0f).put(p[0]).put(p[1] / 2);
  }
  b.put(uint16_t{4}).put(0u).put(1u).put(2u).put(3u);
  b.put(uint16_t{3}).put(3u).put(2u).put(4u);
  return s + b.bytes;
}

void expectQuadAndTriangle(const MeshFile& file, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(file.parts.size(), 1u);
  const TriangleMesh& m = file.parts[0];
  ASSERT_EQ(m.positions.size(), 5u);
  for (size_t v = 0; v < 5; ++v) {
    EXPECT_EQ(m.positions[v].x, kXyz[v][0]);
    EXPECT_EQ(m.positions[v].y, kXyz[v][1]);
    EXPECT_EQ(m.positions[v].z, kXyz[v][2]);
  }
  // The quad 0 1 2 3 fanned from its first corner: (0 1 2) (0 2 3); then the triangle 3 2 4.
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 3, 2, 4}));
  ASSERT_EQ(m.normals.size(), 5u);
  for (const Vec3f& n : m.normals) EXPECT_EQ(n.z, 1.0f);
  ASSERT_EQ(m.uvs.size(), 5u);
  // Vertex 4 is (0.5, 1.5, 0): uv (0.5, 0.75).
  EXPECT_EQ(m.uvs[4].x, 0.5f);
  EXPECT_EQ(m.uvs[4].y, 0.75f);
}

TEST(PlyReader, AsciiAndBothBinaryByteOrdersGiveTheSameMesh) {
  expectQuadAndTriangle(loadMeshFile(test::writeTemp("quad.ply", asciiQuadAndTriangle())), "ascii");
  expectQuadAndTriangle(loadMeshFile(test::writeTemp("quad-le.ply", binaryQuadAndTriangle(false))),
                        "binary little endian");
  expectQuadAndTriangle(loadMeshFile(test::writeTemp("quad-be.ply", binaryQuadAndTriangle(true))),
                        "binary big endian");
}

TEST(PlyReader, APolygonIsAFanFromItsFirstCorner) {
  // A pentagon 0..4 gives (0 1 2) (0 2 3) (0 3 4); a face of two vertices (a line) gives none.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n"
      "1 0 0\n0.25 1 0\n-1 0.5 0\n-1 -0.5 0\n0.25 -1 0\n5 0 1 2 3 4\n2 0 1\n";
  const TriangleMesh m = loadMeshFile(test::writeTemp("pentagon.ply", ply)).parts.at(0);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_TRUE(m.normals.empty());  // no nx ny nz: shaded flat
  EXPECT_TRUE(m.uvs.empty());
}

TEST(PlyReader, OtherElementsAndPropertiesAreSkippedBySize) {
  // Colours, a per-vertex list, an element before the faces and a face list of texture
  // coordinates, in binary: skipping any of them by a wrong size would shift every later value.
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty uchar red\n"
      "property float x\nproperty list uchar short junk\nproperty float y\nproperty float z\n"
      "property double quality\nelement material 1\nproperty float shininess\n"
      "element face 1\nproperty int flags\nproperty list uchar uchar vertex_indices\n"
      "property list uint float texcoord\nend_header\n";
  Body b;
  const float xyz[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}};
  for (const auto& p : xyz) {
    b.put(uint8_t{255}).put(p[0]).put(uint8_t{2}).put(int16_t{-1}).put(int16_t{7});
    b.put(p[1]).put(p[2]).put(0.5);
  }
  b.put(32.0f);
  b.put(int32_t{-9}).put(uint8_t{3}).put(uint8_t{0}).put(uint8_t{1}).put(uint8_t{2});
  b.put(6u);
  for (int i = 0; i < 6; ++i) b.put(0.25f);
  const MeshFile file = loadMeshFile(test::writeTemp("skipped.ply", s + b.bytes));
  const TriangleMesh& m = file.parts.at(0);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[1].x, 2.0f);
  EXPECT_EQ(m.positions[2].y, 4.0f);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  // One part with the default material, named as PLY materials always were: "FILE:".
  ASSERT_EQ(file.materials.size(), 1u);
  EXPECT_EQ(file.materials[0].name, "skipped.ply:");
}

TEST(PlyReader, VertexColoursBecomeTheDiffuseColour) {
  // uchar channels count to 255: 255 0 51 is (1, 0, 0.2); alpha is ignored. Float channels are
  // their values, a negative one 0 with a warning (as for Assimp's files, io/mesh_io.cpp).
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property uchar alpha\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 255 0 51 7\n1 0 0 0 255 0 7\n0 1 0 0 0 255 7\n3 0 1 2\n";
  const MeshFile file = loadMeshFile(test::writeTemp("colours.ply", ply));
  const TriangleMesh& m = file.parts.at(0);
  ASSERT_EQ(m.colors.size(), 3u);
  EXPECT_EQ(m.colors[0].r, 1.0f);
  EXPECT_EQ(m.colors[0].g, 0.0f);
  EXPECT_NEAR(m.colors[0].b, 0.2f, 1e-7);  // 51 / 255 in float
  EXPECT_EQ(m.colors[2].b, 1.0f);
  EXPECT_EQ(file.materials.at(0).surface.kd.pattern, TexturePattern::VertexColor);
  std::string floats =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty float diffuse_red\n"
      "property float diffuse_green\nproperty float diffuse_blue\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  Body b{true, {}};
  for (const float v : {0.f, 0.f, 0.f, 0.5f, -1.f, 0.25f, 1.f, 0.f, 0.f, 1.f, 1.f, 1.f, 0.f, 1.f,
                        0.f, 1.f, 1.f, 1.f})
    b.put(v);
  b.put(uint8_t{3}).put(int32_t{0}).put(int32_t{1}).put(int32_t{2});
  const std::string floatPath = test::writeTemp("float-colours.ply", floats + b.bytes);
  testing::internal::CaptureStderr();
  const TriangleMesh f = loadMeshFile(floatPath).parts.at(0);
  // Replaced, never silently (as a material's negative colour is warned of).
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "glint: warning: mesh " + floatPath +
                ": 1 vertex colour channels are negative or not finite: 0 is used\n");
  ASSERT_EQ(f.colors.size(), 3u);
  EXPECT_EQ(f.colors[0].r, 0.5f);
  EXPECT_EQ(f.colors[0].g, 0.0f);  // -1: 0
  EXPECT_EQ(f.colors[0].b, 0.25f);
  // Without colours the part has none and its diffuse colour stays constant.
  const MeshFile plain = loadMeshFile(test::writeTemp("plain.ply", asciiQuadAndTriangle()));
  EXPECT_TRUE(plain.parts.at(0).colors.empty());
  EXPECT_EQ(plain.materials.at(0).surface.kd.pattern, TexturePattern::Constant);
}

TEST(PlyReader, VerticesNoTriangleUsesAreDropped) {
  // Vertex 1, far away at x = 1000, is named by no face: it would widen the bounds the default
  // camera frames. Vertices 0 2 3 stay, renumbered 0 1 2 in order.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1000 0 0\n1 0 0\n0 1 0\n3 0 2 3\n";
  const TriangleMesh m = loadMeshFile(test::writeTemp("unused.ply", ply)).parts.at(0);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[1].x, 1.0f);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(m.bounds().hi.x, 1.0f);
}

TEST(PlyReader, AnIndexOutsideTheVerticesIsRefused) {
  std::string ascii = asciiQuadAndTriangle();
  ascii.replace(ascii.find("3 3 2 4"), 7, "3 3 2 5");
  EXPECT_NE(test::meshLoadError("index.ply", ascii)
                .find(": face 1 of mesh 0 names vertex 5, but there are only 5"),
            std::string::npos);
  std::string binary = binaryQuadAndTriangle(true);
  // The last index (vertex 4, big endian) becomes 0xffffffff.
  binary.replace(binary.size() - 4, 4, std::string(4, '\xff'));
  EXPECT_NE(test::meshLoadError("index-be.ply", binary)
                .find("names vertex 4294967295, but there are only 5"),
            std::string::npos);
  ascii.replace(ascii.find("3 3 2 5"), 7, "3 3 2 -1");
  EXPECT_NE(test::meshLoadError("negative.ply", ascii).find("names vertex -1"), std::string::npos);
}

TEST(PlyReader, ABodyCutShortIsRefused) {
  // Binary: the last face's 3 indices need 12 bytes; 2 are left. The header's counts still fit
  // (a face takes at least its 2-byte count), so the list's own check finds it.
  const std::string binary = binaryQuadAndTriangle(false);
  EXPECT_NE(test::meshLoadError("cut.ply", binary.substr(0, binary.size() - 10))
                .find("PLY face 1 of 2 (byte " + std::to_string(binary.size() - 12) +
                      "), property vertex_index: its list of 3 values needs 12 bytes, but the "
                      "file has 2 left"),
            std::string::npos);
  // ASCII: the last line (22: 15 header lines, 5 vertices, 2 faces) lacks its last index.
  const std::string ascii = asciiQuadAndTriangle();
  EXPECT_NE(test::meshLoadError("cut-ascii.ply", ascii.substr(0, ascii.size() - 3))
                .find("PLY face 1 of 2 (line 22), property vertex_indices: its list of 3 values "
                      "needs at least 6 bytes, but the file has 4 left"),
            std::string::npos);
}

TEST(PlyReader, CountsThatLieAboutTheFileAreRefusedBeforeAllocating) {
  // 1000 vertices of 8 values declared, 5 given: the header's counts must fit the file.
  std::string ascii = asciiQuadAndTriangle();
  ascii.replace(ascii.find("vertex 5"), 8, "vertex 1000");
  EXPECT_NE(test::meshLoadError("count.ply", ascii)
                .find("declares 1000 \"vertex\" elements, each at least "
                      "16 bytes"),
            std::string::npos);
  // A list count of 4·10^9 (a uint count) in a 200-byte file: refused at the count, nothing
  // allocated or read for it (a misaligned ASCII line once made Assimp allocate 7 GB).
  std::string huge = asciiQuadAndTriangle();
  huge.replace(huge.find("list uchar int"), 14, "list uint int");
  huge.replace(huge.find("3 3 2 4"), 1, "4000000000");
  EXPECT_NE(test::meshLoadError("huge-list.ply", huge)
                .find("its list of 4000000000 values needs at least 8000000000 bytes"),
            std::string::npos);
  // A count that does not fit its type is refused as such: a coordinate where a uchar count
  // belongs (a misaligned line).
  std::string misaligned = asciiQuadAndTriangle();
  misaligned.replace(misaligned.find("4 0 1 2 3"), 1, "0.5");
  EXPECT_NE(test::meshLoadError("misaligned.ply", misaligned)
                .find("PLY face 0 of 2 (line 21), property vertex_indices: \"0.5\" is not a uchar"),
            std::string::npos);
}

TEST(PlyReader, ValuesMustBeFiniteNumbers) {
  std::string ascii = asciiQuadAndTriangle();
  const size_t vertex2 = ascii.find("1 1 0 0 0 1");
  EXPECT_NE(test::meshLoadError("nan.ply", std::string(ascii).replace(vertex2, 1, "nan"))
                .find("vertex 2 of mesh 0 is not finite (nan, 1.000000, 0.000000)"),
            std::string::npos);
  // 1e999 is past double's range; 1e39 past float's: both infinite as floats.
  EXPECT_NE(test::meshLoadError("inf.ply", std::string(ascii).replace(vertex2, 1, "1e999"))
                .find("vertex 2 of mesh 0 is not finite"),
            std::string::npos);
  EXPECT_NE(test::meshLoadError("float.ply", std::string(ascii).replace(vertex2 + 6, 1, "1e39"))
                .find("the normal of vertex 2 of mesh 0 is not finite"),
            std::string::npos);
  EXPECT_NE(test::meshLoadError("word.ply", std::string(ascii).replace(vertex2, 1, "one"))
                .find("PLY vertex 2 of 5 (line 18), property x: \"one\" is not a number"),
            std::string::npos);
  // 1e-999 is below double's range: it reads as 0, a finite value.
  EXPECT_EQ(test::meshLoadError("tiny.ply", std::string(ascii).replace(vertex2 + 4, 1, "1e-999")),
            "(loaded)");
}

TEST(PlyReader, AnAsciiElementHoldsItsLineExactly) {
  // Read as one stream of tokens, a vertex line with one value too many shifted every value
  // after it, and one a value short took the next line's first: a wrong mesh, exit 0. Lines 16
  // to 20 hold the vertices, 21 and 22 the faces.
  const std::string ascii = asciiQuadAndTriangle();
  const size_t vertex2 = ascii.find("1 1 0 0 0 1");
  std::string longLine = ascii;
  longLine.insert(ascii.find('\n', vertex2), " 7");
  EXPECT_NE(test::meshLoadError("long-line.ply", longLine)
                .find("PLY vertex 2 of 5 (line 18): its line holds more values than its "
                      "properties"),
            std::string::npos)
      << test::meshLoadError("long-line.ply", longLine);
  std::string shortLine = ascii;
  shortLine.erase(ascii.rfind(' ', ascii.find('\n', vertex2)), 4);  // " 0.5": v of vertex 2
  EXPECT_NE(
      test::meshLoadError("short-line.ply", shortLine)
          .find("PLY vertex 2 of 5 (line 18), property v: its line ends before its values do"),
      std::string::npos)
      << test::meshLoadError("short-line.ply", shortLine);
  std::string longFace = ascii;
  longFace.replace(ascii.find("3 3 2 4"), 7, "3 3 2 4 1");
  EXPECT_NE(test::meshLoadError("long-face.ply", longFace)
                .find("PLY face 1 of 2 (line 22): its line holds more values than its properties"),
            std::string::npos);
  // Blank lines between elements, blanks at a line's end, CR LF and lone CR line ends are read.
  std::string spaced = ascii;
  spaced.insert(ascii.find("4 0 1 2 3"), "\n  \n");
  spaced.insert(spaced.find('\n', spaced.find("3 3 2 4")), " \t\r");
  EXPECT_EQ(test::meshLoadError("spaced.ply", spaced), "(loaded)");
  std::string crOnly = ascii;
  std::replace(crOnly.begin(), crOnly.end(), '\n', '\r');
  EXPECT_EQ(test::meshLoadError("cr-only.ply", crOnly), "(loaded)");
  std::string crLf;
  for (const char c : ascii) crLf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(test::meshLoadError("cr-lf.ply", crLf), "(loaded)");
  // Lines are counted as the header counts them, lone CRs too.
  std::string crLong = crOnly;
  crLong.insert(crOnly.find('\r', crOnly.find("1 1 0 0 0 1")), " 7");
  EXPECT_NE(test::meshLoadError("cr-long.ply", crLong)
                .find("PLY vertex 2 of 5 (line 18): its line holds more values"),
            std::string::npos)
      << test::meshLoadError("cr-long.ply", crLong);
}

TEST(PlyReader, WhatTheFileLacksIsNamed) {
  EXPECT_NE(test::meshLoadError("empty.ply", "").find("is not a PLY file"), std::string::npos);
  std::string noFaces = asciiQuadAndTriangle();
  noFaces.replace(noFaces.find("element face 2"), 14, "element face 0");
  EXPECT_NE(test::meshLoadError("no-faces.ply", noFaces).find(" has no triangles"),
            std::string::npos);
  std::string noZ = asciiQuadAndTriangle();
  noZ.replace(noZ.find("property float z"), 16, "property float w");
  EXPECT_NE(test::meshLoadError("no-z.ply", noZ).find("its PLY vertex element has no x, y and z"),
            std::string::npos);
}

TEST(PlyReader, BigFilesLogTheirProgressUnlessQuiet) {
  // 1 000 000 faces (the threshold), each the triangle 0 1 2: 13 MB of binary.
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1000000\n"
      "property list uchar int vertex_indices\nend_header\n";
  Body b;
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put(v);
  std::string face;
  face.push_back(3);
  for (const int32_t i : {0, 1, 2}) face.append(reinterpret_cast<const char*>(&i), 4);
  b.bytes.reserve(b.bytes.size() + 13 * 1000000);
  for (int f = 0; f < 1000000; ++f) b.bytes += face;
  const std::string path = test::writeTemp("million.ply", s + b.bytes);
  testing::internal::CaptureStderr();
  EXPECT_EQ(loadMeshFile(path).parts.at(0).triangleCount(), 1000000u);
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("glint: reading mesh " + path +
                     ": 13.0 MB of binary little endian PLY, 3 "
                     "vertices, 1000000 faces\n"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("glint: reading mesh " + path + ": 50%, "), std::string::npos) << log;
  EXPECT_NE(log.find("glint: read mesh " + path + ": 1000000 triangles, 3 vertices in "),
            std::string::npos)
      << log;
  // --quiet lowers the level to warnings: nothing.
  log::setLevel(log::Level::Warning);
  testing::internal::CaptureStderr();
  loadMeshFile(path);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  log::setLevel(log::Level::Info);
  // A small file says nothing.
  testing::internal::CaptureStderr();
  loadMeshFile(test::writeTemp("small.ply", asciiQuadAndTriangle()));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(LoadProgress, OneLineAtTheStartEachQuarterAndTheEnd) {
  testing::internal::CaptureStderr();
  {
    LoadProgress p("mesh m.ply", "what it holds", 100, true);
    p.update(10);  // below a quarter: nothing
    p.update(30);  // 25 %
    p.update(80);  // past two quarters at once: one line, 75 %
    p.update(99);  // the rest is finish()'s
    p.finish("done");
  }
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 4) << log;
  EXPECT_EQ(log.find("glint: reading mesh m.ply: what it holds\n"), 0u) << log;
  EXPECT_NE(log.find("glint: reading mesh m.ply: 25%, "), std::string::npos) << log;
  EXPECT_NE(log.find("glint: reading mesh m.ply: 75%, "), std::string::npos) << log;
  EXPECT_NE(log.find("glint: read mesh m.ply: done in "), std::string::npos) << log;
  testing::internal::CaptureStderr();
  LoadProgress small("mesh s.ply", "", 100, false);
  small.update(100);
  small.finish("done");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace glint
