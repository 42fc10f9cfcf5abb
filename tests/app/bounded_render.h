#pragma once
// `glint render` of a tiny frame in a shell with `timeout` and `ulimit -v`, for the tests that
// hand Glint hostile or broken files: each must end in an image or a clean error, never a
// signal, a hang or a runaway allocation.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "test_util.h"

namespace glint::test {

// AddressSanitizer reserves terabytes of address space for its shadow, so under it the memory
// bound is left out (its own allocator limits still end a runaway allocation).
inline constexpr const char* kMemoryLimit = kAddressSanitizer ? "" : "ulimit -v 4000000; ";

struct BoundedOutcome {
  int status = -1;  // exit status; 124 or 137 for a hang, 128 + N for signal N
  std::string output;
};

// Renders `scene` at `size`×`size`, 1 spp, killed after 20 s, with `args` appended.
inline BoundedOutcome renderBounded(const std::string& scene, int size,
                                    const std::string& args = "") {
  const std::string out = (tempDir() / "bounded-render.exr").string();
  const std::string log = (tempDir() / "bounded-render.log").string();
  const std::string dim = std::to_string(size);
  const std::string cmd = "bash -c '" + std::string(kMemoryLimit) + "exec timeout -s KILL 20 " +
                          std::string(GLINT_BINARY) + " render " + scene + " -o " + out +
                          " --width " + dim + " --height " + dim + " --spp 1 --quiet " + args +
                          "' > " + log + " 2>&1";
  const int status = std::system(cmd.c_str());
  BoundedOutcome o;
  o.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream in(log);
  o.output.assign(std::istreambuf_iterator<char>(in), {});
  return o;
}

}  // namespace glint::test
