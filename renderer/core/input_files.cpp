#include "core/input_files.h"

#include <sys/stat.h>

#include <mutex>
#include <set>
#include <utility>

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

}  // namespace glint
