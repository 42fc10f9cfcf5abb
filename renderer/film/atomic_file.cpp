#include "film/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <utility>

#include "core/error.h"
#include "core/hash.h"
#include "core/input_files.h"
#include "core/interrupt.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// Temporary files start with this, then the host's tag, the writing process's id and a
// counter: a later write in the same directory recognises those whose process has died.
constexpr std::string_view kTemporaryMarker = ".glint-tmp-";
constexpr size_t kNameMax = NAME_MAX;

// 8 hex digits of the host name's hash: on a directory shared by a farm's hosts, a process id
// means something only on its own host.
const std::string& hostTag() {
  static const std::string tag = [] {
    char name[HOST_NAME_MAX + 1] = {};
    ::gethostname(name, sizeof name - 1);
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(hashBytes(name)));
    return std::string(hex);
  }();
  return tag;
}

// ".glint-tmp-HOST-PID-N-NAME.EXT": the final name's stem is cut to keep the whole within
// NAME_MAX, and its extension kept last, since image writers choose the format by it.
std::string temporaryNameFor(const fs::path& finalPath) {
  static std::atomic<unsigned> counter{0};
  const std::string prefix = std::string(kTemporaryMarker) + hostTag() + "-" +
                             std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-";
  const std::string extension = finalPath.extension().string();
  if (prefix.size() + extension.size() > kNameMax)
    throw UsageError("cannot write " + finalPath.string() + ": its extension is too long");
  std::string stem = finalPath.stem().string();
  stem.resize(std::min(stem.size(), kNameMax - prefix.size() - extension.size()));
  return prefix + stem + extension;
}

// Removes this host's temporary files in `dir` whose writing process no longer exists (killed
// before it could clean up). Another live process's files, and other hosts', are left alone.
void removeStaleTemporaries(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kTemporaryMarker, 0) != 0) continue;
    const std::string rest = name.substr(kTemporaryMarker.size());
    if (rest.rfind(hostTag() + "-", 0) != 0) continue;
    const long pid = std::strtol(rest.c_str() + hostTag().size() + 1, nullptr, 10);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

// Whether `dir` (known by device and inode) is due for cleaning of stale temporaries, and is
// now claimed for it: at this process's first write there, and again a minute later for a
// long-lived one (the Python module, a farm worker). Reading the directory at every write made
// a sequence of n frames read n entries per frame. A forked child cleans again, as a process of
// its own.
bool claimCleaningOf(const fs::path& dir) {
  constexpr auto kInterval = std::chrono::minutes(1);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) return true;
  static std::mutex mutex;
  static std::map<std::pair<dev_t, ino_t>, std::chrono::steady_clock::time_point> cleaned;
  static pid_t cleanedBy = 0;
  // A forked child may inherit the lock held by a thread it does not have: it cleans without
  // the record rather than wait forever (cleaning twice is harmless).
  const std::unique_lock lock(mutex, std::try_to_lock);
  if (!lock.owns_lock()) return true;
  if (cleanedBy != ::getpid()) cleaned.clear(), cleanedBy = ::getpid();
  const auto now = std::chrono::steady_clock::now();
  const auto [at, first] = cleaned.try_emplace({st.st_dev, st.st_ino}, now);
  if (first) return true;
  if (now - at->second < kInterval) return false;
  at->second = now;
  return true;
}

// An output may replace only a regular file that this run did not read: renaming over a
// device, a link or a directory entry the user did not mean would destroy it.
void checkReplaceable(const std::string& finalPath) {
  struct stat st {};
  if (::lstat(finalPath.c_str(), &st) != 0) return;  // nothing there yet
  if (!S_ISREG(st.st_mode))
    throw UsageError("refusing to write " + finalPath + ": it exists and is " +
                     fileKind(st.st_mode) + ", which an output never replaces");
  if (isInputFile(finalPath))
    throw UsageError("refusing to write " + finalPath + ": it is one of this run's inputs");
  // Renaming over a file needs only the directory's permission: a file the user may not write
  // (0444, or another user's in a shared directory) would be replaced all the same.
  if (::faccessat(AT_FDCWD, finalPath.c_str(), W_OK, AT_EACCESS) != 0 && errno == EACCES) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    throw UsageError("refusing to replace " + finalPath +
                     ": it is not writable by this user (mode " + mode + ")");
  }
}

// Gives the temporary file the permission bits, owner and group of the file it replaces. The
// owner and group are kept where the process may set them (root, or the owner itself for a
// group it is in); the mode always.
void keepModeOf(const std::string& finalPath, const std::string& tmp) {
  struct stat old {};
  if (::stat(finalPath.c_str(), &old) != 0) return;  // a new file
  if (::chmod(tmp.c_str(), old.st_mode & 07777) != 0)
    throw GlintError("cannot set the mode of " + tmp + ": " + std::strerror(errno));
  struct stat now {};
  if (::stat(tmp.c_str(), &now) == 0 && (now.st_uid != old.st_uid || now.st_gid != old.st_gid) &&
      ::chown(tmp.c_str(), old.st_uid, old.st_gid) != 0)
    (void)!::chown(tmp.c_str(), static_cast<uid_t>(-1), old.st_gid);  // the group alone, if it may
  // chown may clear the set-id bits: set the mode again.
  (void)::chmod(tmp.c_str(), old.st_mode & 07777);
}

void fsyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) throw GlintError("cannot open " + path + " to sync it: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0 && !directory) throw GlintError("cannot sync " + path + ": " + std::strerror(err));
}

// The directory an output goes into ("." for a bare name).
fs::path directoryOf(const fs::path& target) {
  return target.parent_path().empty() ? "." : target.parent_path();
}

}  // namespace

void checkOutputPath(const std::string& finalPath) {
  // A name cut at a NUL by the C calls below would replace another file (Python's Frame.write
  // of "notes.txt\0.exr" overwrote notes.txt); other control characters would reach terminals.
  checkPathCharacters(finalPath, "output file");
  const fs::path target(finalPath);
  const fs::path dir = directoryOf(target);
  if (!fs::is_directory(dir))
    throw UsageError("cannot write " + finalPath + ": directory " + dir.string() +
                     " does not exist");
  // Found now, not by the rename after the work: the temporary file's name is kept short.
  const long nameMax = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  const size_t name = target.filename().string().size();
  if (name > size_t(nameMax > 0 ? nameMax : NAME_MAX))
    throw UsageError("cannot write " + printablePath(finalPath) + ": its name is " +
                     std::to_string(name) + " bytes; file names here have at most " +
                     std::to_string(nameMax > 0 ? nameMax : NAME_MAX));
  if (finalPath.size() >= PATH_MAX)
    throw UsageError("cannot write " + printablePath(finalPath) + ": the path is " +
                     std::to_string(finalPath.size()) + " bytes; paths have fewer than " +
                     std::to_string(PATH_MAX));
  checkReplaceable(finalPath);
  // The temporary file the write will make, made and removed now: a directory the user may not
  // write, or on a read-only file system, is found before the render rather than after it.
  const std::string probe = (dir / temporaryNameFor(target)).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw UsageError("cannot write " + finalPath + ": no file can be made in " + dir.string() +
                     " (" + std::strerror(errno) + ")");
  ::close(fd);
  ::unlink(probe.c_str());
}

bool nameOneFile(const std::string& a, const std::string& b) {
  const auto where = [](const std::string& p) {
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? fs::absolute(p).lexically_normal() : canonical;
  };
  struct stat sa {};
  struct stat sb {};
  const bool sameInode = ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 &&
                         sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  return sameInode || where(a) == where(b);
}

void checkOutputPaths(const std::vector<NamedOutput>& outputs) {
  const auto asked = [](const NamedOutput& o) { return !o.path.empty() && o.path != "-"; };
  const NamedOutput* toStandardOutput = nullptr;
  for (size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k].path == "-") {
      if (toStandardOutput)
        throw UsageError(toStandardOutput->option + " - and " + outputs[k].option +
                         " - both name standard output: it can carry one of them");
      toStandardOutput = &outputs[k];
    }
    if (!asked(outputs[k])) continue;
    for (size_t j = 0; j < k; ++j)
      if (asked(outputs[j]) && nameOneFile(outputs[j].path, outputs[k].path))
        throw UsageError(outputs[j].option + " " + outputs[j].path + " and " + outputs[k].option +
                         " " + outputs[k].path +
                         " name one file: each output needs a file of its own");
  }
  for (const NamedOutput& o : outputs)
    if (asked(o)) checkOutputPath(o.path);
}

namespace {
// The process's standard output, kept by checkCommandOutputs for the output named "-"; −1: not
// kept (it is file descriptor 1 itself).
int keptStandardOutput = -1;
}  // namespace

void checkCommandOutputs(const std::vector<NamedOutput>& outputs) {
  checkOutputPaths(outputs);
  if (keptStandardOutput >= 0 || std::none_of(outputs.begin(), outputs.end(),
                                              [](const NamedOutput& o) { return o.path == "-"; }))
    return;
  std::fflush(stdout);
  const int kept = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
  if (kept < 0) throw UsageError("standard output is not open, and an output names it (-)");
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    const int error = errno;
    ::close(kept);
    throw GlintError(std::string("cannot send the report to standard error: ") +
                     std::strerror(error));
  }
  keptStandardOutput = kept;
}

void writeFileAtomically(const std::string& finalPath,
                         const std::function<void(const std::string&)>& write) {
  checkOutputPath(finalPath);
  const fs::path target(finalPath);
  const fs::path dir = directoryOf(target);
  if (claimCleaningOf(dir)) removeStaleTemporaries(dir);
  const std::string tmp = (dir / temporaryNameFor(target)).string();
  const interrupt::TemporaryFile removedIfInterrupted(tmp);
  try {
    write(tmp);
    keepModeOf(finalPath, tmp);
    fsyncPath(tmp, false);
    checkReplaceable(finalPath);  // again: something may have appeared there while we wrote
    if (std::rename(tmp.c_str(), finalPath.c_str()) != 0)
      throw GlintError("cannot rename " + tmp + " to " + finalPath + ": " + std::strerror(errno));
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  fsyncPath(dir.string(), true);  // make the rename itself durable (best effort)
}

void writeTextFileAtomically(const std::string& finalPath, const std::string& text) {
  if (finalPath == "-") {  // CLI.md: JSON outputs take `-` for standard output
    if (keptStandardOutput < 0) {
      std::fwrite(text.data(), 1, text.size(), stdout);
      if (std::fflush(stdout) != 0)
        throw GlintError(std::string("cannot write to standard output: ") + std::strerror(errno));
      return;
    }
    for (size_t written = 0; written < text.size();) {
      const ssize_t n = ::write(keptStandardOutput, text.data() + written, text.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw GlintError(std::string("cannot write to standard output: ") +
                         (n < 0 ? std::strerror(errno) : "nothing was written"));
      written += size_t(n);
    }
    return;
  }
  writeFileAtomically(finalPath, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw GlintError("cannot write " + finalPath + ": " + std::strerror(errno));
  });
}

}  // namespace glint
