// Mesh files that lie: faces naming vertices that do not exist give a clean error naming the
// file, never a crash or a read of memory that is not the mesh's.
#include "io/mesh_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/error.h"
#include "test_util.h"

namespace glint {
namespace {

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

// The message of the error loading `bytes` as `name` gives, or "(loaded)".
std::string loadError(const std::string& name, const std::string& bytes) {
  const std::string path = (test::tempDir() / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  try {
    loadMeshFile(path);
    return "(loaded)";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.what();
  }
}

TEST(MeshFile, FacesNamingMissingVerticesAreRefused) {
  // Seen segfaulting render, info and validate: an index far past the end, one just past it
  // (which read uninitialised memory), a negative one, and the same in a binary file.
  for (const auto& [name, bytes] :
       {std::pair{"far.ply", asciiPly("3 0 1 99999")}, std::pair{"next.ply", asciiPly("3 0 1 3")},
        std::pair{"negative.ply", asciiPly("3 0 1 -1")},
        std::pair{"binary.ply", binaryPly(123456789)}, std::pair{"binneg.ply", binaryPly(-7)}})
    EXPECT_NE(loadError(name, bytes), "(loaded)") << name;
  // The same file with a valid face loads: one triangle.
  EXPECT_EQ(loadError("good.ply", asciiPly("3 0 1 2")), "(loaded)");
}

}  // namespace
}  // namespace glint
