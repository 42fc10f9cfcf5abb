// Mesh files that lie: faces naming vertices that do not exist, headers declaring more than the
// file holds, content that is not the format its name says, files too large or not regular give
// a clean error naming the file, never a crash, a hang or a read of memory that is not the mesh's.
#include "io/mesh_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/gltf_subset.h"
#include "io/mesh_limits.h"
#include "test_util.h"

namespace glint {
namespace {

using json = nlohmann::json;

const char* kVertices = "0 0 0\n1 0 0\n0 1 0\n";

std::string asciiPly(const std::string& face) {
  return std::string(
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
             "property float y\nproperty float z\nelement face 1\n"
             "property list uchar int vertex_indices\nend_header\n") +
         kVertices + face + "\n";
}

std::string binaryPly(int32_t badIndex) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  s.push_back(3);
  const int32_t idx[3] = {0, 1, badIndex};
  s.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return s;
}

TEST(MeshFile, FacesNamingMissingVerticesAreRefused) {
  // Seen segfaulting render, info and validate: an index far past the end, one just past it
  // (which read uninitialised memory), a negative one, and the same in a binary file.
  for (const auto& [name, bytes] :
       {std::pair{"far.ply", asciiPly("3 0 1 99999")}, std::pair{"next.ply", asciiPly("3 0 1 3")},
        std::pair{"negative.ply", asciiPly("3 0 1 -1")},
        std::pair{"binary.ply", binaryPly(123456789)}, std::pair{"binneg.ply", binaryPly(-7)}})
    EXPECT_NE(test::meshLoadError(name, bytes), "(loaded)") << name;
  // The same file with a valid face loads: one triangle.
  EXPECT_EQ(test::meshLoadError("good.ply", asciiPly("3 0 1 2")), "(loaded)");
}

// A binary PLY header of `vertices` float3 vertices and `faces` triangle faces (uchar count,
// int indices), followed by `bodyBytes` zero bytes.
std::string binaryPlyDeclaring(const std::string& vertices, const std::string& faces,
                               size_t bodyBytes) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertices +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces +
         "\nproperty list uchar int vertex_indices\nend_header\n" + std::string(bodyBytes, '\0');
}

// Assimp's invalid/OutOfMemory.off: a face count of 353535235358 that its OFF reader reserved
// and looped over until the machine's memory ran out (a hang of minutes, then the OOM killer).
const char* kOutOfMemoryOff =
    "OFF\n353535235358 6 0\n-0.5 -0.5 0.5\n0.5 -0.5 0.5\n-0.5 0.5 0.5\n0.5 0.5 0.5\n";

TEST(MeshFile, OnlyTheDocumentedFormatsAreRead) {
  // The OFF reader is never reached, whatever the file holds; nor are Assimp's other 40.
  for (const char* name : {"hang.off", "model.lwo", "scene.x", "noextension"}) {
    const std::string message = test::meshLoadError(name, kOutOfMemoryOff);
    EXPECT_NE(message.find("Glint reads OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb), Collada "
                           "(.dae), FBX (.fbx), 3DS (.3ds), AC3D (.ac), STL (.stl), Milkshape 3D "
                           "(.ms3d) and X3D (.x3d)"),
              std::string::npos)
        << message;
  }
  // Extensions compare without case: the triangle of asciiPly loads from a .PLY too.
  EXPECT_EQ(test::meshLoadError("upper.PLY", asciiPly("3 0 1 2")), "(loaded)");
}

TEST(MeshFile, ForeignContentBehindAGltfNameIsRefused) {
  // .gltf and .glb are claimed by Assimp's glTF 1 and glTF 2 readers; when neither recognised
  // the file, Assimp offered it to every reader by content, and the OFF reader took this one.
  // Glint parses glTF itself first (io/gltf_subset.h), so OFF bytes stop there.
  EXPECT_NE(test::meshLoadError("off.gltf", kOutOfMemoryOff).find("not glTF JSON"),
            std::string::npos);
  EXPECT_NE(test::meshLoadError("off.glb", kOutOfMemoryOff).find("not a GLB 2 file"),
            std::string::npos);
  // JSON that neither glTF reader recognises (no "asset") is refused before Assimp's search by
  // content: its readers of the extension are asked first.
  const std::string message = test::meshLoadError("empty.gltf", "{}");
  EXPECT_NE(message.find("its content is not .gltf"), std::string::npos) << message;
}

TEST(MeshFile, PlyElementCountsMustFitInTheFile) {
  // 10^9 faces of at least 1 byte (an empty list's uchar count) in a 100-byte body: Assimp's
  // binary PLY reader took 3.5 GB in 20 s and went on.
  EXPECT_NE(test::meshLoadError("faces.ply", binaryPlyDeclaring("3", "1000000000", 100))
                .find("declares 1000000000 \"face\" elements, each at least 1 byte, but the file "
                      "has 100 bytes after its header"),
            std::string::npos);
  // 5·10^8 ASCII vertices of 3 values (at least 2 bytes each: a digit and a separator).
  std::string ascii = asciiPly("3 0 1 2");
  ascii.replace(ascii.find("vertex 3"), 8, "vertex 500000000");
  EXPECT_NE(test::meshLoadError("ascii.ply", ascii).find("each at least 6 bytes"),
            std::string::npos);
  // Past 2^32 - 1 Assimp's count would wrap: refused as such.
  EXPECT_NE(test::meshLoadError("wrap.ply", binaryPlyDeclaring("4294967299", "1", 49))
                .find("more than the 4294967295"),
            std::string::npos);
  // The bound is exact: 3 vertices of 12 bytes and a face of at least 1 byte (an empty list's
  // count) need 37 bytes after the header; 36 is refused, 37 passes (Assimp then reads it).
  const std::string short36 = binaryPlyDeclaring("3", "1", 36);
  const std::string exact37 = binaryPlyDeclaring("3", "1", 37);
  EXPECT_THROW(checkPlyCounts("p.ply", short36, short36.size()), GlintError);
  EXPECT_NO_THROW(checkPlyCounts("p.ply", exact37, exact37.size()));
  // A lone CR ends a header line for Assimp: a count hidden after one in a comment is seen.
  const std::string hidden =
      "ply\nformat binary_little_endian 1.0\ncomment x\relement face "
      "1000000000\nproperty uchar c\nend_header\n";
  EXPECT_THROW(checkPlyCounts("h.ply", hidden, hidden.size()), GlintError);
}

TEST(MeshFile, APlyHeaderThatNeverEndsIsRefused) {
  // Assimp 5.2.5's PLY reader never returns on a header without end_header, even this one
  // (found by glint_fuzz_mesh; tests/fuzz/regressions-mesh/ply-*-no-end-header.bin).
  EXPECT_NE(test::meshLoadError("noend.ply",
                                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n")
                .find("its PLY header has no end_header line"),
            std::string::npos);
}

TEST(MeshFile, APlyHeaderMustBeMadeOfPly10Lines) {
  // Assimp's reader never returned from a binary file whose header repeated and garbled its
  // lines (regressions-mesh/ply-garbled-header-lines-hang.bin): each malformed line is refused,
  // while a stray line of text (as Blender 2.47 wrote) is read past, as Assimp does.
  const auto header = [](const std::string& lines) {
    return "ply\n" + lines +
           "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           kVertices + "3 0 1 2\n";
  };
  const auto error = [&](const std::string& lines) {
    return test::meshLoadError("header.ply", header(lines));
  };
  EXPECT_EQ(error("format ascii 1.0\nCreated by Blender3D 247\n"), "(loaded)");
  EXPECT_NE(error("format ascii 1.0\nformat ascii 1.0\n").find("is a second format line"),
            std::string::npos);
  EXPECT_NE(error("format binary_little_endian 2.0\n").find("is not \"format ascii|"),
            std::string::npos);
  EXPECT_NE(error("format ascii 1.0\nelement facy uchar c\n").find("is not \"element NAME COUNT\""),
            std::string::npos);
  EXPECT_NE(
      error("format ascii 1.0\nelement e 1\nproperty quad x\n").find("is not \"property TYPE"),
      std::string::npos);
  EXPECT_NE(error("").find("has no format line"), std::string::npos);
  EXPECT_NE(test::meshLoadError("first.ply", "ply\x82\n" + header("format ascii 1.0\n").substr(4))
                .find("should be \"ply\" alone"),
            std::string::npos);
}

TEST(MeshFile, AFaceWithoutVerticesIsRefused) {
  // A face list of length 0 made Assimp's triangulation assert and abort the process (SIGABRT,
  // exit 134 from glint render), beside a valid triangle too (found by glint_fuzz_mesh).
  std::string ply = asciiPly("3 0 1 2") + "0\n";
  ply.replace(ply.find("element face 1"), 14, "element face 2");
  EXPECT_NE(test::meshLoadError("empty-face.ply", ply).find("face 1 of mesh 0 has no vertices"),
            std::string::npos);
}

TEST(MeshFile, GltfIsReducedToItsGeometryBeforeAssimpReadsIt) {
  // Skins, animations, cameras, morph targets and vertex attributes other than positions,
  // normals and the first two texture coordinate sets never reach Assimp: its glTF 2 reader
  // dereferenced a null pointer for a skin without inverseBindMatrices (SEGV;
  // tests/fuzz/regressions-mesh/gltf-skin-*.bin). Materials reach it as factors and their base
  // colour, metallic-roughness, occlusion and emissive textures (by index alone); normal maps
  // and other textures are dropped.
  // (This file's base colour texture names a texture that does not exist, so it goes too.)
  const std::string in = R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "skins": [{"joints": [0]}], "animations": [], "cameras": [{}],
    "materials": [{"name": "m", "doubleSided": true, "normalTexture": {"index": 0},
      "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "baseColorTexture": {"index": 0}},
      "extensions": {"KHR_materials_volume": {"attenuationDistance": 2, "thicknessTexture": {}},
                     "KHR_materials_sheen": {}}}],
    "textures": [], "images": [], "samplers": [], "extras": {"x": 1},
    "nodes": [{"mesh": 0, "skin": 0, "camera": 0, "weights": [1], "translation": [1, 2, 3]}],
    "meshes": [{"weights": [1], "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1,
      "TEXCOORD_0": 5, "TEXCOORD_1": 6, "JOINTS_0": 2}, "indices": 3, "material": 0,
      "targets": [{"POSITION": 4}]}]}],
    "accessors": [], "bufferViews": [], "buffers": []})";
  EXPECT_EQ(nlohmann::json::parse(gltfSubset("m.gltf", in)), nlohmann::json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "translation": [1, 2, 3]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 5,
                                               "TEXCOORD_1": 6},
                                "indices": 3, "material": 0}]}],
    "materials": [{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]},
                   "extensions": {"KHR_materials_volume": {"attenuationDistance": 2}}}],
    "accessors": [], "bufferViews": [], "buffers": []})"));
}

TEST(MeshFile, MalformedGltfTexturesAreLeftOutBeforeAssimpReadsThem) {
  // An embedded image whose mimeType is not image/png or image/jpeg made Assimp's reader strcmp
  // a null pointer (SEGV; regressions-mesh/glb-embedded-image-mimetype-not-image-segv.bin); a
  // texture naming an image that does not exist is as malformed. Either way the textures,
  // images, samplers and the materials' references to them go; the factors stay.
  for (const char* images : {R"([{"bufferView": 0, "mimeType": "image.png"}])", "[]"}) {
    const json subset = json::parse(gltfSubset("m.gltf", std::string(
                                                             R"({"asset": {"version": "2.0"},
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1],
                                              "baseColorTexture": {"index": 0}}}],
      "textures": [{"source": 0}], "images": )") + images + R"(,
      "bufferViews": [{"buffer": 0, "byteLength": 4}], "buffers": [{"byteLength": 4}]})"));
    EXPECT_FALSE(subset.contains("textures")) << images;
    EXPECT_FALSE(subset.contains("images")) << images;
    EXPECT_EQ(subset["materials"][0], json::parse(R"({"pbrMetallicRoughness":
      {"baseColorFactor": [1, 0, 0, 1]}})"));
  }
  // Well formed, they stay.
  const json kept = json::parse(gltfSubset("m.gltf", R"({"asset": {"version": "2.0"},
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0}], "images": [{"bufferView": 0, "mimeType": "image/png"}],
    "bufferViews": [{"buffer": 0, "byteLength": 4}], "buffers": [{"byteLength": 4}]})"));
  EXPECT_EQ(kept["images"].size(), 1u);
}

TEST(MeshFile, OnlyTrianglePrimitivesOfAGltfReachAssimp) {
  // Points (0), lines (1), line loops (2) and strips (3) are dropped; triangles (no mode, 4),
  // strips (5) and fans (6) stay. A line loop whose index passed the vertices crashed
  // Assimp's reader (regressions-mesh/gltf-line-loop-index-past-vertices-segv.bin).
  const json subset = json::parse(gltfSubset("m.gltf", R"({"asset": {"version": "2.0"},
    "meshes": [{"primitives": [{"mode": 0}, {"mode": 1}, {"mode": 2}, {"mode": 3}, {},
                               {"mode": 4}, {"mode": 5}, {"mode": 6}, {"mode": "4"}]}]})"));
  EXPECT_EQ(subset["meshes"][0]["primitives"],
            json::parse(R"([{}, {"mode": 4}, {"mode": 5}, {"mode": 6}])"));
  const std::string error =
      test::meshLoadError("line-loop.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 2}]}],
    "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3"}]})");
  EXPECT_NE(error, "(loaded)");
}

TEST(MeshFile, VertexNormalsOfObjPlyAndRealFilesAreKept) {
  // OBJ vn and PLY nx ny nz, one normal per vertex, and a real third-party model's.
  const std::string obj = test::writeTemp(
      "normals.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\nf 1//1 2//2 3//3\n");
  const TriangleMesh fromObj = loadMeshFile(obj).parts.at(0);
  ASSERT_EQ(fromObj.normals.size(), fromObj.positions.size());
  // Vertex (1, 0, 0) carries vn 2: (0.6, 0, 0.8).
  for (size_t v = 0; v < fromObj.positions.size(); ++v)
    if (fromObj.positions[v].x == 1) {
      EXPECT_FLOAT_EQ(fromObj.normals[v].x, 0.6f);
      EXPECT_FLOAT_EQ(fromObj.normals[v].z, 0.8f);
    }
  const std::string ply = test::writeTemp(
      "normals.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
  const TriangleMesh fromPly = loadMeshFile(ply).parts.at(0);
  ASSERT_EQ(fromPly.normals.size(), 3u);
  EXPECT_FLOAT_EQ(fromPly.normals[1].z, 1.0f);
  // Without normals the mesh is shaded flat.
  EXPECT_TRUE(
      loadMeshFile(test::writeTemp("flat.ply", asciiPly("3 0 1 2"))).parts.at(0).normals.empty());
  const std::string wuson = "/usr/share/assimp/models/OBJ/WusonOBJ.obj";
  if (!std::filesystem::exists(wuson)) GTEST_SKIP() << "assimp-testmodels is not installed";
  for (const TriangleMesh& real : loadMeshFile(wuson).parts) {
    EXPECT_EQ(real.normals.size(), real.positions.size());
    EXPECT_GT(real.triangleCount(), 1000u);
  }
}

TEST(MeshFile, AMeshWithoutNormalsIsFlatBesideMeshesThatKeepTheirs) {
  // A floor without vn beside a smooth part made the whole file flat (a ball rendered in
  // facets). glTF 2.0 (3.7.2.1) gives a primitive without NORMAL flat normals; the others keep
  // their own. A bent quad (two triangles meeting at a ridge) without normals, beside a triangle
  // with tilted vn: the triangle keeps its vn, each half of the quad its own face's normal.
  const std::string obj =
      test::writeTemp("smooth_and_flat.obj",
                      "o Smooth\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\n"
                      "f 1//1 2//2 3//3\n"
                      "o Ridge\nv 0 0 5\nv 1 0 5\nv 1 1 6\nv 0 1 6\nv 0 2 5\nv 1 2 5\n"
                      "f 4 5 6\nf 4 6 7\nf 7 6 9\nf 7 9 8\n");
  const TriangleMesh mesh = loadMeshFile(obj).parts.at(0);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  const float s = 1 / std::sqrt(2.0f);  // the ridge's faces rise and fall at 45 degrees
  int smooth = 0, rising = 0, falling = 0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3f& p0 = mesh.positions[mesh.indices[t]];
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.indices[t + size_t(c)];
      const Vec3f& n = mesh.normals[v];
      if (p0.z < 1) {
        ++smooth;
        if (mesh.positions[v].x == 1) EXPECT_FLOAT_EQ(n.x, 0.6f);  // vn 2, as the file gives
        continue;
      }
      // Every corner of a face of the ridge carries that face's normal, whichever face shares
      // its position.
      const Vec3f edge1 = mesh.positions[mesh.indices[t + 1]] - p0;
      const Vec3f edge2 = mesh.positions[mesh.indices[t + 2]] - p0;
      const Vec3f face = normalize(cross(edge1, edge2));
      EXPECT_NEAR(n.x, face.x, 1e-6f);
      EXPECT_NEAR(n.y, face.y, 1e-6f);
      EXPECT_NEAR(n.z, face.z, 1e-6f);
      EXPECT_NEAR(std::fabs(n.y), s, 1e-6f);
      ++(n.y < 0 ? rising : falling);
    }
  }
  EXPECT_EQ(smooth, 3);
  EXPECT_EQ(rising, 6);
  EXPECT_EQ(falling, 6);
}

TEST(MeshFile, AnObjsSmoothingGroupsShadeItSmoothWithoutNormals) {
  // An octahedron without vn in smoothing group 1 rendered faceted: Assimp's reader drops `s`
  // lines. Each vertex now takes its four faces' normals averaged, which for the octahedron is
  // the direction to the vertex itself. In groups of its own (s 1 ... s 8), each face is flat.
  const char* corners[8] = {"1 3 5", "3 2 5", "2 4 5", "4 1 5", "3 1 6", "2 3 6", "4 2 6", "1 4 6"};
  const std::string vertices = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n";
  std::string smooth = vertices + "s 1\n", apart = vertices;
  for (int f = 0; f < 8; ++f) {
    smooth += "f " + std::string(corners[f]) + "\n";
    apart += "s " + std::to_string(f + 1) + "\nf " + corners[f] + "\n";
  }
  const TriangleMesh round = loadMeshFile(test::writeTemp("octahedron.obj", smooth)).parts.at(0);
  ASSERT_EQ(round.normals.size(), round.positions.size());
  EXPECT_EQ(round.positions.size(), 6u);  // one normal per vertex: joined into six
  for (size_t v = 0; v < round.positions.size(); ++v) {
    EXPECT_NEAR(round.normals[v].x, round.positions[v].x, 1e-6f);
    EXPECT_NEAR(round.normals[v].y, round.positions[v].y, 1e-6f);
    EXPECT_NEAR(round.normals[v].z, round.positions[v].z, 1e-6f);
  }
  const TriangleMesh faceted =
      loadMeshFile(test::writeTemp("octahedron-apart.obj", apart)).parts.at(0);
  ASSERT_EQ(faceted.normals.size(), faceted.positions.size());
  const float third = 1 / std::sqrt(3.0f);  // each face's normal is (±1, ±1, ±1)/√3
  for (const Vec3f& n : faceted.normals) {
    EXPECT_NEAR(std::fabs(n.x), third, 1e-6f);
    EXPECT_NEAR(std::fabs(n.y), third, 1e-6f);
    EXPECT_NEAR(std::fabs(n.z), third, 1e-6f);
  }
}

TEST(MeshFile, ANodeThatMirrorsItsMeshKeepsItsTrianglesWoundOutward) {
  // glTF 2.0 (3.5.2): under a transform of negative determinant a triangle winds clockwise
  // about its outward side. Assimp flattened it wound as before, its geometric normal turned
  // against its vertex normals (a normal map bent the wrong way; glass would be inside out).
  // One mesh placed plain and mirrored in x: every triangle of both must wind counter-clockwise
  // about its vertex normal.
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(normals), sizeof normals);
  const std::string gltf = test::writeTemp("mirrored.gltf", R"({"asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0, 1]}],
      "nodes": [{"mesh": 0, "translation": [-2, 0, 0]},
                {"mesh": 0, "translation": [2, 0, 0], "scale": [-1, 1, 1]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
      "buffers": [{"uri": "data:application/octet-stream;base64,)" +
                                                                test::base64(buffer) + R"(",
                   "byteLength": 72}],
      "bufferViews": [{"buffer": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}]})");
  const TriangleMesh mesh = loadMeshFile(gltf).parts.at(0);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  int mirrored = 0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3f& p0 = mesh.positions[mesh.indices[t]];
    const Vec3f winding =
        cross(mesh.positions[mesh.indices[t + 1]] - p0, mesh.positions[mesh.indices[t + 2]] - p0);
    EXPECT_GT(dot(winding, mesh.normals[mesh.indices[t]]), 0) << "triangle " << t / 3;
    mirrored += p0.x > 0;
  }
  EXPECT_EQ(mirrored, 1);
}

TEST(MeshFile, NonFiniteVertexValuesOfAnObjAreRefusedAtTheirLine) {
  // Assimp reads nan, inf and 1e39 (past float's range) in an OBJ file as 0 without a word: a
  // vertex moved to the origin, a texture coordinate to the image's corner. PLY files refuse the
  // same values; an OBJ file's are refused at their line before Assimp reads it.
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (const auto& [line, named] :
       {std::pair<std::string, std::string>{"vt nan nan", ":7: vt holds nan"},
        {"vt 1e39 0", ":7: vt holds 1e39"},
        {"v inf 0 0", ":7: v holds inf"},
        {"vn nan 0 1", ":7: vn holds nan"},
        {"vn 0 -1e40 1", ":7: vn holds -1e40"}}) {
    const std::string message =
        test::meshLoadError("bad-value.obj", triangle + line + "\nf 1/1 2/2 3/3\n");
    EXPECT_NE(message.find("bad-value.obj" + named + ", which is not a finite float"),
              std::string::npos)
        << line << ": " << message;
  }
  // Small and large numbers, a comment after them, and vertex colours load.
  EXPECT_EQ(
      test::meshLoadError("edge.obj", triangle + "v 1e3 -2.5e-3 1e-45 # far\nv 0 0 1 0.5 0.5 0.5\n"
                                                 "f 1/1 2/2 3/3\n"),
      "(loaded)");
}

TEST(MeshFile, VertexLinesAssimpMisreadsAreRefusedAtTheirLine) {
  // Assimp read "0x1p3" (and "3.1+e2") as the number its first characters make, 0 (and 3.1),
  // and skipped a vertex of two numbers or of words, its faces then refused as "vertex index
  // out of range"; a face of two vertices among triangles failed its validation, naming no
  // line. Each is refused at its line.
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (const auto& [line, named] :
       {std::pair<std::string, std::string>{"v 0x1p3 0 0",
                                            ":7: v holds 0x1p3, which is not a decimal number"},
        {"v 3.1+e2 0 0", ":7: v holds 3.1+e2, which is not a decimal number"},
        {"v abc def ghi", ":7: v holds abc, which is not a decimal number"},
        {"v 0 0", ":7: v holds 2 numbers; a vertex is x y z, x y z w or x y z r g b"},
        {"vt 0.5", ":7: vt holds 1 number; a texture coordinate is u v or u v w"},
        {"vn 0 1", ":7: vn holds 2 numbers; a normal is x y z"},
        {"v .5 0 0", ":7: v holds .5, which Assimp does not read as a number (write 0.5)"},
        {"f 1 2", ":7: f gives 2 vertices; a face has at least 3 (a line is written l)"},
        {"v 1 \\\n 2", ":7: v holds 2 numbers"}}) {  // joined lines: named by the first
    const std::string message =
        test::meshLoadError("misread.obj", triangle + line + "\nf 1/1 2/2 3/3\n");
    EXPECT_NE(message.find("misread.obj" + named), std::string::npos) << line << ": " << message;
  }
  // A comma for the point (as some exporters write), a w, u v w, a line continued with '\'
  // and an empty face (which Assimp skips) load.
  EXPECT_EQ(test::meshLoadError("lenient.obj", triangle + "v 0,5 1 2\nv 1 2 3 1\nvt 0.5 0.5 0\n"
                                                          "v 1 0 \\\n 0\nf\nf 1/1 2/2 \\\n3/3\n"),
            "(loaded)");
}

TEST(MeshFile, FaceTextureAndNormalIndicesPastTheirLinesAreRefusedAtTheirLine) {
  // Assimp refuses a face's vertex index past the v lines, but read a vt or vn index past its
  // lines as another vertex's or none, without a word (the texture mapped wrong, exit 0).
  const std::string quad =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  for (const auto& [face, named] :
       {std::pair<std::string, std::string>{
            "f 1/1 2/2 3/3 4/5", ":10: a face gives vt index 5, but the file has 4 vt lines"},
        {"f 1/1 2/2 3/3 4/100000000",
         ":10: a face gives vt index 100000000, but the file has 4 vt lines"},
        {"f 1/1 2/2 3/3 4/-9", ":10: a face gives vt index -9, but only 4 vt lines come before it"},
        {"f 1//1 2//1 3//50000000",
         ":10: a face gives vn index 50000000, but the file has 1 vn lines"},
        {"f 1/0 2/2 3/3", ":10: a face gives vt index 0, but OBJ indices start at 1"}}) {
    const std::string message = test::meshLoadError("bad-index.obj", quad + face + "\n");
    EXPECT_NE(message.find("bad-index.obj" + named), std::string::npos) << face << ": " << message;
  }
  // Every index in range, relative ones too: loaded.
  EXPECT_EQ(test::meshLoadError("good-index.obj", quad + "f 1/1/1 2/2/1 3/3/1 4/-1/-1\n"),
            "(loaded)");
  EXPECT_EQ(test::meshLoadError("relative.obj", quad + "f -4/-4/-1 -3/-3/-1 -2/-2/-1 -1/-1/-1\n"),
            "(loaded)");
}

TEST(MeshFile, AMissingMaterialLibraryOrMaterialIsNamedInAWarning) {
  // Assimp gives the faces its default grey without a word; the render goes on, saying why.
  // (red.png is missing too: a warning of its own.)
  const std::string dir = (test::tempDir() / "missing-mtl").string();
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/m.obj") << "mtllib nowhere.mtl\nmtllib here.mtl\nusemtl red\n"
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl blue\nf 1 3 2\n";
  std::ofstream(dir + "/here.mtl") << "newmtl red\nKd 1 0 0\nmap_Kd -s 2 2 1 -o 0.5 0 0 -s 1 1 1 "
                                      "red.png\n";
  const auto r =
      test::runGlint("render " + dir + "/m.obj --width 8 --height 8 --spp 1 -o " + dir + "/m.exr");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("m.obj: its material library \"nowhere.mtl\" is not a file beside it; "
                          "its materials are left out"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("m.obj: material \"blue\" is used but no material library defines it"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("material \"red\""), std::string::npos) << r.output;
  // Map options Assimp parses and drops: the texture was read at scale 1 without a word.
  EXPECT_NE(r.output.find("here.mtl gives map options -s, -o (line 3 first), which Glint does not "
                          "apply"),
            std::string::npos)
      << r.output;
}

TEST(MeshFile, NonFiniteNormalsAndTextureCoordinatesOfAGltfAreRefusedNamingTheVertex) {
  // A glTF's floats reach Glint as stored. A NaN normal would be merged or dropped by Assimp's
  // vertex welding; a NaN texture coordinate was read as (0, 0) without a word.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto triangle = [](const std::array<float, 9>& normals, const std::array<float, 6>& uvs) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
    buffer.append(reinterpret_cast<const char*>(normals.data()), sizeof(float) * 9);
    buffer.append(reinterpret_cast<const char*>(uvs.data()), sizeof(float) * 6);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}]}],
      "buffers": [{"uri": "data:application/octet-stream;base64,)" +
           test::base64(buffer) + R"(", "byteLength": 96}],
      "bufferViews": [{"buffer": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 72, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}]})";
  };
  const std::array<float, 9> up = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::array<float, 6> uvs = {0, 0, 1, 0, 0, 1};
  const std::string normal =
      test::meshLoadError("nan-normal.gltf", triangle({0, 0, 1, nan, 0, 1, 0, 0, 1}, uvs));
  EXPECT_NE(normal.find("the normal of vertex 1 of mesh 0 is not finite"), std::string::npos)
      << normal;
  const std::string uv = test::meshLoadError("nan-uv.gltf", triangle(up, {0, 0, 1, 0, nan, 1}));
  EXPECT_NE(uv.find("the texture coordinates of vertex 2 of mesh 0 are not finite"),
            std::string::npos)
      << uv;
  EXPECT_EQ(test::meshLoadError("finite.gltf", triangle(up, uvs)), "(loaded)");
}

TEST(MeshFile, GltfThatIsNotStrictJsonOrNotVersion2IsRefused) {
  // A usage error (exit 2, as for every other bad mesh), not a runtime failure.
  const auto error = [](const std::string& name, const std::string& text) {
    try {
      gltfSubset(name, text);
      return std::string("(accepted)");
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(error("one.gltf", R"({"asset": {"version": "1.0"}})"),
            "mesh one.gltf: glTF 1.0 is not supported; Glint reads glTF 2.0 (asset.version is "
            "\"1.0\")");
  // Cesium's glTF 1.0 exporters write the version as a number (CesiumMilkTruck.gltf of
  // assimp-testmodels): it was read on as 2.0 until "nodes is not an array".
  EXPECT_EQ(error("int.gltf", R"({"asset": {"version": 1}, "nodes": {"n": {}}})"),
            "mesh int.gltf: glTF 1.0 is not supported; Glint reads glTF 2.0 (asset.version is 1)");
  // glTF 1.0's objects keyed by name, with no version to tell.
  EXPECT_EQ(error("keyed.gltf", R"({"nodes": {"n": {}}})"),
            "mesh keyed.gltf: its \"nodes\" is an object keyed by name, as in glTF 1.0, which is "
            "not supported; Glint reads glTF 2.0");
  EXPECT_EQ(error("three.gltf", R"({"asset": {"version": "3.0"}})"),
            "mesh three.gltf is glTF 3.0; Glint reads glTF 2.0");
  // Invalid UTF-8 in a key: Assimp's reader took the file (and its skin) whole.
  EXPECT_NE(error("utf8.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"a\xff\": 1}")
                .find("mesh utf8.gltf: not glTF JSON: "),
            std::string::npos);
  EXPECT_EQ(error("array.gltf", "[1, 2]"), "mesh array.gltf: not glTF: not a JSON object");
  // 64 levels are read, 65 refused (Assimp's JSON reader recurses once per level).
  const auto nested = [](int depth) {
    return "{\"extras\": " + std::string(size_t(depth - 1), '[') +
           std::string(size_t(depth - 1), ']') + "}";
  };
  EXPECT_EQ(error("64.gltf", nested(64)), "(accepted)");
  EXPECT_EQ(error("65.gltf", nested(65)),
            "mesh 65.gltf: its JSON nests more than 64 levels deep (a glTF file needs about 6)");
  // A GLB of version 1 (Assimp's glTF 1 reader would take it) is not read.
  try {
    glbSubset("one.glb", std::string("glTF\x01\x00\x00\x00", 8));
    ADD_FAILURE() << "a GLB of version 1 was read";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("binary glTF 1.0 is not supported"), std::string::npos)
        << e.what();
  }
}

TEST(MeshFile, FilesOverOneGibibyteAreRefusedUnread) {
  // A sparse file: 1 GiB + 1 byte on paper, no disk blocks, never read.
  const std::filesystem::path path = test::tempDir() / "big.obj";
  std::ofstream(path) << "v 0 0 0\n";
  std::filesystem::resize_file(path, kMaxMeshFileBytes + 1);
  try {
    loadMeshFile(path.string());
    ADD_FAILURE() << "a 1 GiB + 1 byte mesh loaded";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh " + path.string() + " is 1073741825 bytes"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

TEST(MeshFile, FilesAMeshNamesMustBeRegularFiles) {
  // A glTF whose buffer is a FIFO: opening it blocked forever. It is refused as a file Assimp
  // could not open (the message names the buffer's file).
  const std::filesystem::path dir = test::tempDir() / "fifo";
  std::filesystem::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "buffer.bin").c_str(), 0600), 0);
  const std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"uri": "buffer.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}]})";
  const std::string message = test::meshLoadError("fifo/mesh.gltf", gltf);
  EXPECT_NE(message.find("buffer.bin"), std::string::npos) << message;
}

// One triangle in an embedded buffer: 3 float positions, then indices 0, 1 and `third` (uint16).
std::string triangleWithIndices(const char* base64) {
  return std::string(R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"uri": "data:application/octet-stream;base64,)") +
         base64 + R"(", "byteLength": 44}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

TEST(MeshFile, AGlbCutInsideItsJsonChunkIsNamedAsCut) {
  // A GLB 2 header whose JSON chunk claims 100 bytes more than the file holds: the file is GLB 2
  // (it was called "not a GLB 2 file"), cut or damaged.
  const std::string text = R"({"asset": {"version": "2.0"}})";  // 29 bytes
  std::string glb = "glTF";
  const auto put = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  put(2);
  put(uint32_t(20 + text.size()));
  put(uint32_t(text.size() + 100));
  put(0x4E4F534Au);
  glb += text;
  const std::string message = test::meshLoadError("cut.glb", glb);
  EXPECT_NE(message.find("its JSON chunk claims 129 bytes, but the file holds 29 after the "
                         "chunk's header"),
            std::string::npos)
      << message;
}

TEST(MeshFile, AGltfImageWhoseDataUriHoldsNoBytesIsLeftOutNamedSo) {
  // Assimp names such an image with an empty path, which was looked for as a file: "texture
  // /tmp/ is a directory". The triangle renders without its texture.
  std::string gltf =
      triangleWithIndices("AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=");
  gltf.insert(gltf.rfind('}'), R"(, "images": [{"uri": "data:image/png;base64,"}],
    "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness":
      {"baseColorTexture": {"index": 0}}}])");
  gltf.replace(gltf.find(R"("indices": 1})"), 13, R"("indices": 1, "material": 0})");
  testing::internal::CaptureStderr();
  const MeshFile f = loadMeshFile(test::writeTemp("empty-image.gltf", gltf));
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_EQ(f.materials.size(), 1u);
  EXPECT_EQ(f.materials[0].surface.kd.image, nullptr);
  EXPECT_NE(warnings.find("texture left out: a material names an image without a name or bytes"),
            std::string::npos)
      << warnings;
  EXPECT_EQ(warnings.find("directory"), std::string::npos) << warnings;
}

TEST(MeshFile, AGltfIndexPastItsVerticesIsRefusedNotDropped) {
  // Assimp's glTF 2 reader dropped the triangle without a word (assimp-testmodels'
  // IndexOutOfRange rendered a triangle short, exit 0). Indices 0, 1, 3 of 3 vertices: the
  // third index, indices[2], names vertex 3.
  const std::string message = test::meshLoadError(
      "index-past.gltf",
      triangleWithIndices("AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAMAAAA="));
  EXPECT_NE(message.find("index-past.gltf: meshes[0].primitives[0]: indices[2] = 3, but its "
                         "POSITION has 3 vertices"),
            std::string::npos)
      << message;
  // Indices 0, 1, 2 of the same buffer: the one triangle loads.
  const MeshFile ok = loadMeshFile(test::writeTemp(
      "index-in-range.gltf",
      triangleWithIndices("AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=")));
  size_t triangles = 0;
  for (const TriangleMesh& part : ok.parts) triangles += part.indices.size() / 3;
  EXPECT_EQ(triangles, 1u);
  // Assimp's own test file, where installed: 255 in a mesh of 24 vertices.
  const std::string model = "/usr/share/assimp/models/glTF2/IndexOutOfRange/IndexOutOfRange.gltf";
  if (!std::filesystem::exists(model)) return;
  try {
    loadMeshFile(model);
    ADD_FAILURE() << model << " loaded";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find("meshes[0].primitives[0]: indices[0] = 255, but its "
                                         "POSITION has 24 vertices"),
              std::string::npos)
        << e.what();
  }
}

TEST(MeshFile, AGltfSparseIndexIsCheckedAsTheIndexItReplaces) {
  // A sparse accessor's values replace indices by position; Assimp applied an out-of-range one
  // and dropped its triangle without a word. A triangle (3 vertices) with indices `base` and
  // one sparse value `replacement` at position 2.
  const auto triangle = [](uint16_t lastBase, uint16_t replacement) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
    for (const uint16_t v : {uint16_t(0), uint16_t(1), lastBase, uint16_t(0), uint16_t(2),
                             uint16_t(0), replacement, uint16_t(0)})
      buffer.append(reinterpret_cast<const char*>(&v), 2);  // indices, pad, position, pad, value
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [{"uri": "data:application/octet-stream;base64,)" +
           test::base64(buffer) + R"(", "byteLength": 52}],
      "bufferViews": [{"buffer": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                      {"buffer": 0, "byteOffset": 44, "byteLength": 2},
                      {"buffer": 0, "byteOffset": 48, "byteLength": 2}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR",
                     "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                "values": {"bufferView": 3}}}]})";
  };
  const std::string past = test::meshLoadError("sparse-past.gltf", triangle(2, 7));
  EXPECT_NE(past.find("sparse-past.gltf: meshes[0].primitives[0]: indices.sparse.values[0] = 7, "
                      "but its POSITION has 3 vertices"),
            std::string::npos)
      << past;
  // An index out of range that a sparse value replaces is no fault: loaded.
  EXPECT_EQ(test::meshLoadError("sparse-mends.gltf", triangle(9, 2)), "(loaded)");
}

TEST(MeshFile, AGltfBufferOfBadBase64IsRefused) {
  // Assimp decoded what it could and read the rest as zeros: a mesh of degenerate triangles,
  // nothing drawn, exit 0. The indexed triangle's buffer with a character that base64 lacks,
  // and with one after its padding.
  const std::string good = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
  const std::string at = test::meshLoadError(
      "bad-base64.gltf", triangleWithIndices(("AAAA@" + good.substr(5)).c_str()));
  EXPECT_NE(at.find("bad-base64.gltf: buffers[0].uri is a data URI whose base64 has \"@\" at "
                    "character 41"),
            std::string::npos)
      << at;
  const std::string after =
      test::meshLoadError("after-padding.gltf", triangleWithIndices((good + "AA").c_str()));
  EXPECT_NE(after.find("whose base64 has \"A\" at character"), std::string::npos) << after;
  EXPECT_EQ(test::meshLoadError("good-base64.gltf", triangleWithIndices(good.c_str())), "(loaded)");
}

TEST(MeshFile, AGltfUriIsReadAsTheReferenceItIs) {
  // "tri%20angle.bin" names "tri angle.bin" (RFC 3986); Assimp looked for the literal name and
  // refused the mesh. A literal name that is a file is still read as written.
  const std::filesystem::path dir = test::tempDir() / "gltf-uri";
  std::filesystem::create_directories(dir);
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::ofstream(dir / "tri angle.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(positions), sizeof positions);
  for (const char* literal : {"100%.bin", "50%25.bin"})
    std::ofstream(dir / literal, std::ios::binary)
        .write(reinterpret_cast<const char*>(positions), sizeof positions);
  const auto gltf = [&](const std::string& name, const std::string& uri) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [{"uri": ")" + uri +
                               R"(", "byteLength": 36}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]}]})";
    return path;
  };
  // "50%25.bin" decodes to "50%.bin", which is not there: the name as written is read.
  for (const auto& [name, uri] :
       {std::pair<std::string, std::string>{"escaped.gltf", "tri%20angle.bin"},
        {"literal.gltf", "100%.bin"},
        {"escaped-literal.gltf", "50%25.bin"}}) {
    size_t triangles = 0;
    for (const TriangleMesh& part : loadMeshFile(gltf(name, uri)).parts)
      triangles += part.indices.size() / 3;
    EXPECT_EQ(triangles, 1u) << uri;
  }
  // An escaped NUL is refused as a literal one is.
  const std::string nul =
      test::meshLoadError("nul.gltf", test::readFile(gltf("nul-src.gltf", "a.bin%00x")));
  EXPECT_NE(nul.find("buffers[0].uri"), std::string::npos) << nul;
  EXPECT_NE(nul.find("control characters"), std::string::npos) << nul;
}

TEST(MeshFile, QuantizedGltfTextureCoordinatesAreLeftOutWithAWarning) {
  // glTF 2.0 allows TEXCOORD_0 as normalized unsigned bytes; Assimp 5.2.5 read their bytes as
  // floats: the texture's one colour over the mesh, exit 0, without a word. The set is left out
  // and named; the mesh loads, without texture coordinates.
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer += std::string("\0\0\0\0\xff\0\0\0\0\xff\0\0", 12);  // (0, 0), (1, 0), (0, 1), stride 4
  const std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}}]}],
    "buffers": [{"uri": "data:application/octet-stream;base64,)" +
                           test::base64(buffer) + R"(", "byteLength": 48}],
    "bufferViews": [{"buffer": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 12, "byteStride": 4}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5121, "normalized": true, "count": 3,
                   "type": "VEC2"}]})";
  testing::internal::CaptureStderr();
  const MeshFile mesh = loadMeshFile(test::writeTemp("quantized-uv.gltf", gltf));
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_TRUE(mesh.parts[0].uvs.empty());
  EXPECT_NE(warnings.find("quantized-uv.gltf: texture coordinates stored as integers (quantized), "
                          "first meshes[0].primitives[0]'s TEXCOORD_0 (unsigned bytes), are left "
                          "out"),
            std::string::npos)
      << warnings;
}

TEST(MeshFile, AGltfStrideShorterThanItsElementsIsRefused) {
  // glTF 2.0 requires a buffer view's byteStride to hold an element of each accessor reading it;
  // Assimp read the overlapping elements of a shorter one as other geometry, without a word.
  // The triangle's positions are VEC3 floats, 12 bytes: a stride of 8 is refused, 12 loads.
  const std::string triangle =
      triangleWithIndices("AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=");
  const std::string view = R"({"buffer": 0, "byteLength": 36})";
  ASSERT_NE(triangle.find(view), std::string::npos);
  const auto withStride = [&](int stride) {
    std::string text = triangle;
    text.replace(
        text.find(view), view.size(),
        R"({"buffer": 0, "byteLength": 36, "byteStride": )" + std::to_string(stride) + "}");
    return text;
  };
  const std::string message = test::meshLoadError("short-stride.gltf", withStride(8));
  EXPECT_NE(message.find("short-stride.gltf: accessors[0] reads bufferViews[0], whose byteStride 8 "
                         "is less than its 12-byte elements"),
            std::string::npos)
      << message;
  const MeshFile ok = loadMeshFile(test::writeTemp("whole-stride.gltf", withStride(12)));
  size_t triangles = 0;
  for (const TriangleMesh& part : ok.parts) triangles += part.indices.size() / 3;
  EXPECT_EQ(triangles, 1u);
}

TEST(MeshFile, AGltfUriWithAControlCharacterIsRefused) {
  // "buffer.bin\u0000.png" would open buffer.bin: the name is refused whatever follows it.
  const std::string message = test::meshLoadError("uri-nul.gltf", R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "buffer.bin\u0000.png", "byteLength": 36}]})");
  EXPECT_NE(message.find("buffers[0].uri \"buffer.bin\\x00.png\": a file name may not hold "
                         "control characters"),
            std::string::npos)
      << message;
}

TEST(MeshFile, AnObjMaterialLibraryThatIsAFifoIsLeftOutUnopened) {
  // An OBJ naming a FIFO as its material library: Assimp goes on without a library it cannot
  // open, so the file loads with its geometry (and a warning naming the FIFO). alarm() ends the
  // binary if the FIFO is ever opened for reading.
  ::alarm(20);
  const std::filesystem::path dir = test::tempDir() / "fifo-mtl";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "m.mtl").c_str(), 0600), 0);
  std::ofstream(dir / "a.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const MeshFile mesh = loadMeshFile((dir / "a.obj").string());
  size_t triangles = 0;
  for (const TriangleMesh& part : mesh.parts) triangles += part.indices.size() / 3;
  EXPECT_EQ(triangles, 1u);
  ::alarm(0);
}

TEST(MeshFile, AnObjNamingMoreThan4096MaterialsIsRefusedBeforeAssimpReadsIt) {
  // Assimp builds a material for each distinct usemtl name it cannot find and looks names up
  // linearly: 20 000 names took 23 s and 740 MB. 4096 distinct names load (one triangle each);
  // 4097 are refused by the pre-scan, naming the file.
  const auto obj = [](int names) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < names; ++i) text += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
    return text;
  };
  EXPECT_EQ(test::meshLoadError("names4096.obj", obj(4096)), "(loaded)");
  EXPECT_NE(test::meshLoadError("names4097.obj", obj(4097))
                .find("names4097.obj names more than 4096 materials (\"usemtl\" lines with "
                      "distinct names); Glint reads at most 4096 from one OBJ file"),
            std::string::npos);
  // Names its material library defines count too.
  std::string mtl;
  for (int i = 0; i < 4097; ++i) mtl += "newmtl n" + std::to_string(i) + "\n";
  test::writeTemp("many.mtl", mtl);
  EXPECT_NE(test::meshLoadError("library.obj", "mtllib many.mtl\n" + obj(1)).find("many.mtl names"),
            std::string::npos);
}

TEST(MeshFile, AnObjNamingMaterialLibrariesMoreThan4096TimesIsRefusedBeforeAssimpReadsIt) {
  // Assimp opens and parses a line's libraries for each mtllib line: two million lines naming
  // one small library took 17 s. 4096 lines load; a 4097th is refused at its line, after a tab
  // as after a space (Assimp reads both). A line's words are libraries too (the OBJ format lists
  // several on a line), each read once however often the line repeats it, and the times the
  // lines name libraries are bounded alike.
  test::writeTemp("one.mtl", "newmtl m\nKd 1 0 0\n");
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  for (const char* blank : {" ", "\t"}) {
    std::string lines;
    for (int i = 0; i < 4096; ++i) lines += std::string("mtllib") + blank + "one.mtl\n";
    EXPECT_EQ(test::meshLoadError("lines4096.obj", lines + triangle), "(loaded)");
    const std::string refused =
        test::meshLoadError("lines4097.obj", lines + "mtllib" + blank + "one.mtl\n" + triangle);
    EXPECT_NE(refused.find("lines4097.obj:4097: more than 4096 mtllib lines"), std::string::npos)
        << refused;
  }
  std::string repeated;
  for (int line = 0; line < 40; ++line) {
    repeated += "mtllib";
    for (int i = 0; i < 4097; ++i) repeated += " one.mtl";
    repeated += "\n";
  }
  EXPECT_EQ(test::meshLoadError("repeated.obj", repeated + triangle), "(loaded)");
  std::string words;
  for (int line = 0; line < 2; ++line) {
    words += "mtllib";
    for (int i = 0; i < 2049; ++i) words += " lib" + std::to_string(i) + ".mtl";
    words += "\n";
  }
  const std::string many = test::meshLoadError("words.obj", words + triangle);
  EXPECT_NE(many.find("words.obj names material libraries more than 4096 times"), std::string::npos)
      << many;
}

TEST(MeshFile, OnlyAnObjsMaterialLibraryNameIsReadAsSeveralFiles) {
  // A glTF buffer named "p.bin n.bin" beside p.bin and n.bin is missing, not the two joined;
  // an OBJ's one library named with a trailing space, or by an absolute path (Assimp opens
  // "dir/a.mtl " and "dir//abs/a.mtl"), is read.
  test::writeTemp("p.bin", std::string(36, '\0'));
  test::writeTemp("n.bin", std::string(36, '\0'));
  std::string gltf = triangleWithIndices("AAAA");
  const std::string uri = "data:application/octet-stream;base64,AAAA";
  gltf.replace(gltf.find(uri), uri.size(), "p.bin n.bin");
  EXPECT_NE(test::meshLoadError("joined.gltf", gltf), "(loaded)");
  const std::string red = test::writeTemp("red.mtl", "newmtl red\nKd 1 0 0\n");
  for (const std::string& line : {std::string("mtllib red.mtl \n"), "mtllib " + red + "\n"}) {
    const MeshFile f = loadMeshFile(
        test::writeTemp("one-library.obj", line + "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\n"
                                                  "f 1 2 3\n"));
    ASSERT_EQ(f.materials.size(), 1u) << line;
    EXPECT_EQ(f.materials[0].surface.kd.constant.r, 1.0f) << line;
    EXPECT_EQ(f.materials[0].surface.kd.constant.g, 0.0f) << line;
  }
}

}  // namespace
}  // namespace glint
