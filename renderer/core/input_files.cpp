#include "core/input_files.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <utility>

#include "core/error.h"

namespace glint {

namespace {

std::mutex mutex;
std::set<std::pair<dev_t, ino_t>>& inputs() {
  static std::set<std::pair<dev_t, ino_t>> files;
  return files;
}

}  // namespace

void noteInputFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  const std::lock_guard lock(mutex);
  inputs().insert({st.st_dev, st.st_ino});
}

bool isInputFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  const std::lock_guard lock(mutex);
  return inputs().count({st.st_dev, st.st_ino}) != 0;
}

std::string readInputFile(const std::string& path, size_t maxBytes, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  // A named input that cannot be opened is a bad argument, as a missing one is (exit 2, as for
  // the EXRs, textures and meshes a run reads); a read that fails part-way is a runtime failure.
  if (!in) throw UsageError("cannot open " + path + ": " + std::strerror(errno));
  noteInputFile(path);
  std::string bytes;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.append(buffer, static_cast<size_t>(in.gcount()));
    if (bytes.size() > maxBytes)
      throw UsageError(path + " is larger than " + std::to_string(maxBytes >> 20) +
                       " MiB, the limit of " + what);
  }
  if (in.bad()) throw GlintError("cannot read " + path + ": " + std::strerror(errno));
  return bytes;
}

}  // namespace glint
