#include "core/input_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
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
std::set<std::pair<dev_t, ino_t>>& replaceableInputs() {
  static std::set<std::pair<dev_t, ino_t>> files;
  return files;
}

bool isControl(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

std::string mib(uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

// Opens `path` for reading without waiting (a FIFO without a writer would block open()), then
// makes reads wait again. Returns -1 with errno set.
int openWithoutWaiting(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

// The checks before opening, shared by both entry points; `pipes`: FIFOs and pipes pass.
struct stat statInput(const std::string& path, uint64_t maxBytes, const std::string& what,
                      bool pipes) {
  checkPathCharacters(path, what);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw UsageError(what + " not found: " + path);
    throw UsageError("cannot read " + what + " " + path + ": " + std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode) && !(pipes && S_ISFIFO(st.st_mode)))
    throw UsageError(
        what + " " + path + " is " + fileKind(st.st_mode) +
        (pipes ? "; it must be a regular file or a pipe" : "; it must be a regular file"));
  if (S_ISREG(st.st_mode) && uint64_t(st.st_size) > maxBytes)
    throw UsageError(what + " " + path + " is " + std::to_string(st.st_size) +
                     " bytes; the limit is " + mib(maxBytes));
  return st;
}

}  // namespace

void checkPathCharacters(const std::string& path, const std::string& what) {
  for (size_t i = 0; i < path.size(); ++i)
    if (isControl(path[i])) {
      char code[8];
      std::snprintf(code, sizeof code, "\\x%02x", static_cast<unsigned char>(path[i]));
      throw UsageError(what + " " + inQuotes(printablePath(path)) +
                       ": a file name may not hold control characters; this one has " + code +
                       (path[i] == '\0' ? " (NUL)" : "") + " at byte " + std::to_string(i));
    }
}

std::string printablePath(const std::string& path) {
  std::string out;
  for (const char c : path) {
    if (!isControl(c)) {
      out += c;
      continue;
    }
    char code[8];
    std::snprintf(code, sizeof code, "\\x%02x", static_cast<unsigned char>(c));
    out += code;
  }
  return excerpt(out);
}

uint64_t checkInputFile(const std::string& path, uint64_t maxBytes, const std::string& what) {
  const struct stat st = statInput(path, maxBytes, what, false);
  const int fd = openWithoutWaiting(path);
  if (fd < 0) throw UsageError("cannot read " + what + " " + path + ": " + std::strerror(errno));
  ::close(fd);
  noteInputFile(path);
  return uint64_t(st.st_size);
}

const char* fileKind(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

void noteInputFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  const std::lock_guard lock(mutex);
  inputs().insert({st.st_dev, st.st_ino});
}

InputReadAlone::InputReadAlone(const std::string& path) : path_(path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  const std::lock_guard lock(mutex);
  wasNoted_ = inputs().count({st.st_dev, st.st_ino}) != 0;
}

InputReadAlone::~InputReadAlone() {
  struct stat st {};
  if (wasNoted_ || ::stat(path_.c_str(), &st) != 0) return;
  const std::lock_guard lock(mutex);
  inputs().erase({st.st_dev, st.st_ino});
}

void allowReplacingInput(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  const std::lock_guard lock(mutex);
  replaceableInputs().insert({st.st_dev, st.st_ino});
}

bool isInputFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  const std::lock_guard lock(mutex);
  return inputs().count({st.st_dev, st.st_ino}) != 0 &&
         replaceableInputs().count({st.st_dev, st.st_ino}) == 0;
}

std::string readInputFile(const std::string& path, size_t maxBytes, const std::string& what) {
  const struct stat st = statInput(path, maxBytes, what, true);
  const int fd = openWithoutWaiting(path);
  if (fd < 0) throw UsageError("cannot read " + what + " " + path + ": " + std::strerror(errno));
  noteInputFile(path);
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      throw GlintError("cannot read " + what + " " + path + ": " + std::strerror(error));
    }
    if (n == 0) break;
    bytes.append(buffer, size_t(n));
    if (bytes.size() > maxBytes) {
      ::close(fd);
      throw UsageError(what + " " + path + " is larger than " + mib(maxBytes) + ", the limit");
    }
  }
  ::close(fd);
  if (bytes.empty() && S_ISFIFO(st.st_mode))
    throw UsageError(what + " " + path + " is a FIFO or pipe that nobody wrote to");
  return bytes;
}

}  // namespace glint
