// Assimp's own broken files (Debian's assimp-testmodels: invalid/ and the deliberately broken
// glTF 2 models) as a scene's mesh: `glint render` must give an image (exit 0) or a clean error
// naming the file (exit 2) within 20 s and 4 GB of address space; never a signal or a hang.
// invalid/OutOfMemory.off once hung the loader until memory ran out.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

// AddressSanitizer reserves terabytes of address space for its shadow, so under it the memory
// bound is left out (its own allocator limits still end a runaway allocation).
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kMemoryLimit = "";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr const char* kMemoryLimit = "";
#else
constexpr const char* kMemoryLimit = "ulimit -v 4000000; ";
#endif
#else
constexpr const char* kMemoryLimit = "ulimit -v 4000000; ";
#endif

struct Outcome {
  int status = -1;  // exit status; 124 or 137 for a hang, 128 + N for signal N
  std::string output;
};

// Renders a 4×4 frame of a scene holding `mesh`, in a shell with `timeout` and `ulimit -v`.
Outcome renderMesh(const fs::path& mesh) {
  const std::string scene = test::writeTemp(
      "assimp-model.json",
      R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "materials": {"m": {"type": "phong"}},
          "objects": [{"type": "mesh", "file": ")" +
          mesh.string() + R"(", "material": "m"}]})");
  const std::string out = (test::tempDir() / "assimp-model.exr").string();
  const std::string log = (test::tempDir() / "assimp-model.log").string();
  const std::string cmd = "bash -c '" + std::string(kMemoryLimit) + "exec timeout -s KILL 20 " +
                          std::string(GLINT_BINARY) + " render " + scene + " -o " + out +
                          " --width 4 --height 4 --spp 1 --quiet' > " + log + " 2>&1";
  const int status = std::system(cmd.c_str());
  Outcome o;
  o.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream in(log);
  o.output.assign(std::istreambuf_iterator<char>(in), {});
  return o;
}

void expectImageOrCleanError(const fs::path& mesh) {
  const Outcome o = renderMesh(mesh);
  EXPECT_TRUE(o.status == 0 || o.status == 2) << mesh << ": exit " << o.status << "\n" << o.output;
  if (o.status == 2) {
    EXPECT_NE(o.output.find(mesh.string()), std::string::npos) << mesh << ": " << o.output;
  }
}

TEST(AssimpModels, EveryInvalidFileGivesAnImageOrACleanError) {
  if (!fs::is_directory(kModels / "invalid"))
    GTEST_SKIP() << "assimp-testmodels is not installed (" << kModels / "invalid"
                 << " is missing); tools/lib.sh installs it";
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kModels / "invalid")) {
    expectImageOrCleanError(entry.path());
    ++files;
  }
  EXPECT_GE(files, 15u) << "assimp-testmodels 5.2.5 has 15 files in invalid/";
}

TEST(AssimpModels, EveryBrokenGltfGivesAnImageOrACleanError) {
  if (!fs::is_directory(kModels / "glTF2"))
    GTEST_SKIP() << "assimp-testmodels is not installed; tools/lib.sh installs it";
  for (const char* mesh :
       {"IndexOutOfRange/IndexOutOfRange.gltf", "IndexOutOfRange/AllIndicesOutOfRange.gltf",
        "MissingBin/BoxTextured.gltf", "RecursiveNodes/RecursiveNodes.gltf",
        "SchemaFailures/sceneWrongType.gltf", "TestNoRootNode/NoScene.gltf",
        "TestNoRootNode/SceneWithoutNodes.gltf", "wrongTypes/badArray.gltf",
        "wrongTypes/badNumber.gltf", "wrongTypes/badUint.gltf", "IncorrectVertexArrays/Cube.gltf",
        "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "issue_3269/texcoord_crash.gltf"})
    expectImageOrCleanError(kModels / "glTF2" / mesh);
}

TEST(AssimpModels, OutOfMemoryOffIsRefusedByItsFormat) {
  if (!fs::exists(kModels / "invalid/OutOfMemory.off"))
    GTEST_SKIP() << "assimp-testmodels is not installed; tools/lib.sh installs it";
  const Outcome o = renderMesh(kModels / "invalid/OutOfMemory.off");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("Glint reads OBJ (.obj), PLY (.ply) and glTF 2.0 (.gltf, .glb)"),
            std::string::npos)
      << o.output;
}

}  // namespace
}  // namespace glint
