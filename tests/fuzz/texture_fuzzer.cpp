// libFuzzer target over Glint's own texture readers (docs/hardening.md): the input's first byte
// picks the format (0 PNG, 1 JPEG, 2 Radiance HDR: libpng's, libjpeg's and Glint's readers), the
// rest are the file's bytes, opened as a texture embedded in a glTF is (texture_fuzz_input.h:
// the header, the texture's budget, every row). The only acceptable outcomes are a texture, or
// a GlintError naming the file. Crashes, sanitizer reports, other exceptions, hangs and
// allocations over the fuzzer's limit are bugs. Files a reader leaves to OpenImageIO are skipped
// (kept out of the corpus): its module is not what this target tests. libpng and libjpeg are not
// instrumented: coverage guides the fuzzer through Glint's code only.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "film/image_limits.h"
#include "texture_fuzz_input.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Well below the fuzzer's 2 GB RSS limit, with room for ASan's shadow and quarantine.
  glint::setImageMemoryBudget(uint64_t{1} << 29);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bool skipped = false;
  const std::string problem = glint::fuzz::textureReadProblem(
      std::string(reinterpret_cast<const char*>(data), size), &skipped);
  if (!problem.empty()) {
    std::fprintf(stderr, "glint_fuzz_texture: %s\n", problem.c_str());
    std::abort();
  }
  return skipped ? -1 : 0;
}
