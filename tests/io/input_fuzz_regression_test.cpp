// Mesh, EXR and texture inputs that once hung, crashed or exhausted a reader, or that the fuzzers
// of tests/fuzz/ found (docs/hardening.md): tests/fuzz/regressions-mesh/ in glint_fuzz_mesh's
// input form, tests/fuzz/regressions-exr/ as EXR files, tests/fuzz/regressions-texture/ in
// glint_fuzz_texture's. Each must meet its fuzzer's oracle: a mesh, image or texture that is
// whole, or an error naming the file. One ctest entry per file.
#include <gtest/gtest.h>

#include <filesystem>

#include "fuzz/exr_fuzz_input.h"
#include "fuzz/mesh_fuzz_input.h"
#include "fuzz/texture_fuzz_input.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(GLINT_SOURCE_DIR) / "tests/fuzz";

std::vector<std::string> filesIn(const std::string& dir) {
  return test::fileNamesIn(kFuzzDir / dir);
}

std::string testName(const testing::TestParamInfo<std::string>& input) {
  std::string id = fs::path(input.param).stem().string();
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return id;
}

class MeshFuzzRegression : public testing::TestWithParam<std::string> {};

TEST_P(MeshFuzzRegression, LoadsOrNamesTheFile) {
  const fs::path dir = test::tempDir() / "mesh-regression";
  fs::create_directories(dir);
  const std::string input = test::readFile(kFuzzDir / "regressions-mesh" / GetParam());
  ASSERT_FALSE(input.empty());
  EXPECT_EQ(fuzz::meshLoadProblem(fuzz::writeMeshInput(dir, input).string()), "");
}

INSTANTIATE_TEST_SUITE_P(Inputs, MeshFuzzRegression, testing::ValuesIn(filesIn("regressions-mesh")),
                         testName);

class ExrFuzzRegression : public testing::TestWithParam<std::string> {};

TEST_P(ExrFuzzRegression, ReadsOrNamesTheFile) {
  const fs::path path = kFuzzDir / "regressions-exr" / GetParam();
  EXPECT_EQ(fuzz::exrReadProblem(path.string(), (test::tempDir() / "merged.exr").string()), "");
}

INSTANTIATE_TEST_SUITE_P(Inputs, ExrFuzzRegression, testing::ValuesIn(filesIn("regressions-exr")),
                         testName);

class TextureFuzzRegression : public testing::TestWithParam<std::string> {};

TEST_P(TextureFuzzRegression, ReadsOrNamesTheFile) {
  const std::string input = test::readFile(kFuzzDir / "regressions-texture" / GetParam());
  bool skipped = true;
  EXPECT_EQ(fuzz::textureReadProblem(input, &skipped), "");
  EXPECT_FALSE(skipped);  // a regression input reaches Glint's reader
}

INSTANTIATE_TEST_SUITE_P(Inputs, TextureFuzzRegression,
                         testing::ValuesIn(filesIn("regressions-texture")), testName);

}  // namespace
}  // namespace glint
