// libFuzzer target over the mesh-file loader, loadMeshFile (io/mesh_io.h; docs/hardening.md).
// Inputs take the form of mesh_fuzz_input.h: a format byte, a PLY, OBJ, glTF or GLB file and
// optionally the file it names (an OBJ's m.mtl, a glTF's m.bin), written to a private temporary
// directory. The only acceptable outcomes are a triangle mesh whose indices name its vertices
// and whose positions are finite, or a GlintError naming the file. Crashes, sanitizer reports,
// other exceptions, hangs and runaway allocations are bugs. Assimp is not instrumented, so
// coverage guides the fuzzer through Glint's checks only; Assimp's crashes, hangs and
// allocations are caught all the same.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "fuzz_temp_dir.h"
#include "mesh_fuzz_input.h"

namespace {
std::filesystem::path gDir;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  gDir = glint::fuzz::makePrivateTempDir("glint-fuzz-mesh-");
  glint::fuzz::addHostileFiles(gDir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return -1;  // -1: keep it out of the corpus
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::string mesh = glint::fuzz::writeMeshInput(gDir, input).string();
  if (const std::string problem = glint::fuzz::meshLoadProblem(mesh); !problem.empty()) {
    std::fprintf(stderr, "glint_fuzz_mesh: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
