#pragma once
// A private temporary directory for one fuzzer process, PREFIX + its pid, removed at exit. A
// crash ends the process with _Exit, past atexit, so each start also removes the directories of
// fuzzer processes with this prefix that no longer exist.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace glint::fuzz {

inline std::filesystem::path& tempDirPath() {
  static std::filesystem::path dir;
  return dir;
}

inline std::filesystem::path makePrivateTempDir(std::string_view prefix) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const char* digits = name.data() + prefix.size();
    pid_t pid = 0;
    const auto [end, error] = std::from_chars(digits, name.data() + name.size(), pid);
    if (error != std::errc() || end != name.data() + name.size() || pid <= 0) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
  }
  fs::path& dir = tempDirPath();
  dir = fs::temp_directory_path() / (std::string(prefix) + std::to_string(getpid()));
  fs::remove_all(dir);  // left by an earlier process with this pid
  fs::create_directory(dir);
  std::atexit([] {
    std::error_code ignored;
    fs::remove_all(tempDirPath(), ignored);
  });
  return dir;
}

// Hostile neighbours for the inputs to name (their names are in the dictionaries): FIFOs, which
// a reader that opened them would wait on for ever (libFuzzer reports the hang), and links to
// /dev/zero, which never ends. Every input file check must refuse them unopened.
inline void addHostileFiles(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const char* ext : {"ply", "obj", "gltf", "glb", "bin", "mtl", "png", "tif"}) {
    ::mkfifo((dir / (std::string("fifo.") + ext)).c_str(), 0600);
    fs::create_symlink("/dev/zero", dir / (std::string("zero.") + ext), ec);
  }
}

}  // namespace glint::fuzz
