#pragma once
// Helpers shared by the test suites: scenes from strings, temporary files, running the binary.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "film/image_file.h"
#include "io/mesh_io.h"
#include "io/scene_loader.h"

namespace glint::test {

// Whether the tests run under AddressSanitizer, which reserves terabytes of address space for
// its shadow memory (no process runs below an address-space limit) and makes tracing ~10x slower.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

// The random rays of an agreement check between structures: a twentieth under AddressSanitizer.
// There the check looks for memory and undefined-behaviour faults, which a twentieth of the rays
// reach through the same code; the full count's agreement is the Release suite's to check.
inline constexpr int agreementRays(int releaseRays) {
  return kAddressSanitizer ? releaseRays / 20 : releaseRays;
}

// This test process's directory for temporary files, removed when the process ends with every
// test passed; after a failure it is kept, with what the failing test wrote.
inline std::filesystem::path tempDir() {
  struct Directory {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("glint-test-" + std::to_string(::getpid()));
    Directory() {
      // An earlier test process with the same pid (pids wrap) may have left files here: a FIFO
      // that mkfifo then refused, a file a test expects to create.
      std::filesystem::remove_all(path);
      std::filesystem::create_directories(path);
    }
    ~Directory() {
      const ::testing::UnitTest* tests = ::testing::UnitTest::GetInstance();
      if (tests->failed_test_count() > 0 || tests->ad_hoc_test_result().Failed()) return;
      std::error_code ignored;  // at exit: what cannot be removed stays, without an exception
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Directory dir;
  return dir.path;
}

inline std::string writeTemp(const std::string& name, const std::string& text) {
  const auto path = tempDir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// The message of the error loading `bytes` written as mesh file `name` gives (it must name the
// file), or "(loaded)".
inline std::string meshLoadError(const std::string& name, const std::string& bytes) {
  const std::string path = writeTemp(name, bytes);
  try {
    loadMeshFile(path);
    return "(loaded)";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.what();
  }
}

// An 8 × 8 grey PNG in the temporary folder, black in its left half and white in its right: as
// an opacity matte (materials/cutout.h), holes where u < 0.5 and solid where u > 0.5 (filtering
// blends the two only within a texel of u = 0.5, and of u = 0 where the image repeats).
// Written once: a scene that read it makes it one of the run's inputs, which Glint refuses to
// overwrite.
inline std::string writeHalfMatte() {
  static const std::string path = [] {
    const std::string p = (tempDir() / "half_matte.png").string();
    std::vector<uint16_t> codes;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) codes.insert(codes.end(), 3, x < 4 ? 0 : 255);
    writeRgbImage(p, 8, 8, 8, codes);
    return p;
  }();
  return path;
}

// RFC 4648 base64, for the data URIs of glTF files the tests write.
inline std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);  // bytes in this group
    uint32_t v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The names of the regular files in `dir`, sorted (for parameterised tests over a folder).
inline std::vector<std::string> fileNamesIn(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file()) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline Scene sceneFromText(const std::string& text) {
  return loadSceneText(text, "scene.json", GLINT_SCENES_DIR);
}

// The message of the SceneError that loading `text` throws, or "(no error)".
inline std::string sceneErrorOf(const std::string& text) {
  try {
    sceneFromText(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together, unless runGlint's `streams` say otherwise
};

// Runs the glint binary through the shell; `environment` (e.g. "LD_DEBUG=files") is set for
// glint alone.
// `streams` the shell's redirection of the rest: standard error into the output by default.
inline RunResult runGlint(const std::string& args, const std::string& environment = "",
                          const std::string& streams = "2>&1") {
  RunResult r;
  const std::string cmd =
      environment + " " + std::string(GLINT_BINARY) + " " + args + " " + streams;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace glint::test
