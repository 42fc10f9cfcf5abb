#include "film/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace glint {

namespace {

std::string temporaryPathFor(const std::filesystem::path& finalPath) {
  static std::atomic<unsigned> counter{0};
  const std::string name = "." + finalPath.filename().string() + ".tmp" +
                           std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                           finalPath.extension().string();
  return (finalPath.parent_path() / name).string();
}

void fsyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) throw GlintError("cannot open " + path + " to sync it: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0 && !directory) throw GlintError("cannot sync " + path + ": " + std::strerror(err));
}

}  // namespace

void writeFileAtomically(const std::string& finalPath,
                         const std::function<void(const std::string&)>& write) {
  const std::filesystem::path target(finalPath);
  const std::filesystem::path dir = target.parent_path().empty() ? "." : target.parent_path();
  if (!std::filesystem::is_directory(dir))
    throw GlintError("cannot write " + finalPath + ": directory " + dir.string() +
                     " does not exist");
  const std::string tmp = temporaryPathFor(target);
  try {
    write(tmp);
    fsyncPath(tmp, false);
    if (std::rename(tmp.c_str(), finalPath.c_str()) != 0)
      throw GlintError("cannot rename " + tmp + " to " + finalPath + ": " + std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  fsyncPath(dir.string(), true);  // make the rename itself durable (best effort)
}

void writeTextFileAtomically(const std::string& finalPath, const std::string& text) {
  writeFileAtomically(finalPath, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw GlintError("cannot write " + finalPath + ": " + std::strerror(errno));
  });
}

}  // namespace glint
