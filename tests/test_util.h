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
#include "io/mesh_io.h"
#include "io/scene_loader.h"

namespace glint::test {

inline std::filesystem::path tempDir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("glint-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
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
  std::string output;  // stdout and stderr together
};

// Runs the glint binary through the shell; `environment` (e.g. "LD_DEBUG=files") is set for
// glint alone.
inline RunResult runGlint(const std::string& args, const std::string& environment = "") {
  RunResult r;
  const std::string cmd = environment + " " + std::string(GLINT_BINARY) + " " + args + " 2>&1";
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
