// libFuzzer target over Glint's EXR readers (docs/hardening.md): the input, written to a file in
// a private temporary directory, goes to readImage, mergeCrops and readResumeState
// (exr_fuzz_input.h). The only acceptable outcomes are an image whose pixel array matches its
// size, a merged frame, a resume state a render could have left, or a GlintError naming the
// file. Crashes, sanitizer reports, other exceptions, hangs and allocations over the fuzzer's
// limit (as the 6.4 GB of a 50 MB EXR declaring a huge data window) are bugs. OpenEXR is not
// instrumented: coverage guides the fuzzer through Glint's code only.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "exr_fuzz_input.h"
#include "film/image_limits.h"
#include "fuzz_temp_dir.h"

namespace {
std::filesystem::path gDir;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  gDir = glint::fuzz::makePrivateTempDir("glint-fuzz-exr-");
  // Well below the fuzzer's 2 GB RSS limit: what Glint accepts must not trip it, and ASan's
  // shadow and quarantine come on top (a 60 s run peaked at 1.9 GB with a 1 GB budget).
  glint::setImageMemoryBudget(uint64_t{1} << 29);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = (gDir / "in.exr").string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const std::string problem = glint::fuzz::exrReadProblem(path, (gDir / "merged.exr").string());
  if (!problem.empty()) {
    std::fprintf(stderr, "glint_fuzz_exr: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
