// Outputs never destroy what they must not: what is not a regular file, the run's inputs, or the
// previous file when the write fails; temporary names fit NAME_MAX and do not outlive a kill.
#include "film/atomic_file.h"

#include <grp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/input_files.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = test::tempDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

size_t temporaries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    n += e.path().filename().string().rfind(".glint-tmp-", 0) == 0;
  return n;
}

TEST(AtomicFile, RefusesToReplaceWhatIsNotARegularFile) {
  const fs::path dir = freshDir("not-regular");
  const fs::path target = dir / "target.json";
  std::ofstream(target) << "target";
  const fs::path link = dir / "link.json", fifo = dir / "fifo.json", sub = dir / "sub.json";
  fs::create_symlink(target, link);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directory(sub);
  for (const fs::path& p : {link, fifo, sub})
    EXPECT_THROW(writeTextFileAtomically(p.string(), "new"), UsageError) << p;
  // Each is still what it was, and the link's target is untouched.
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(sub));
  EXPECT_EQ(slurp(target), "target");
  EXPECT_EQ(temporaries(dir), 0u);
}

TEST(AtomicFile, RefusesToReplaceAnInputUnderAnyOfItsNames) {
  const fs::path dir = freshDir("inputs");
  const fs::path input = dir / "scene.json", otherName = dir / "hardlink.json";
  std::ofstream(input) << "the scene";
  fs::create_hard_link(input, otherName);
  noteInputFile(input.string());
  EXPECT_THROW(writeTextFileAtomically(input.string(), "overwritten"), UsageError);
  EXPECT_THROW(writeTextFileAtomically(otherName.string(), "overwritten"), UsageError);
  EXPECT_EQ(slurp(input), "the scene");
  // An ordinary file beside it is replaced as usual.
  writeTextFileAtomically((dir / "out.json").string(), "out");
  EXPECT_EQ(slurp(dir / "out.json"), "out");
}

TEST(AtomicFile, NamesUpToNameMaxCanBeWritten) {
  // 251 + ".exr" = 255 bytes, the longest name Linux allows: the temporary name, which adds a
  // marker, host, process and counter, must still fit.
  const fs::path dir = freshDir("long");
  const fs::path target = dir / (std::string(251, 'n') + ".exr");
  writeTextFileAtomically(target.string(), "long");
  EXPECT_EQ(slurp(target), "long");
  EXPECT_EQ(temporaries(dir), 0u);
}

// Starts a child that writes `name` in `dir` and stops inside the write, its temporary file on
// disk: killed at once (`die`), or waiting to be killed. Returns the child's pid.
pid_t childInsideAWrite(const fs::path& dir, const std::string& name, bool die) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    writeFileAtomically((dir / name).string(), [&](const std::string& tmp) {
      std::ofstream(tmp) << "partial";
      if (die) ::kill(::getpid(), SIGKILL);
      (void)!::write(ready[1], "r", 1);
      ::pause();
    });
    ::_exit(0);
  }
  ::close(ready[1]);
  if (!die) {
    char c;
    (void)!::read(ready[0], &c, 1);
  } else {
    ::waitpid(pid, nullptr, 0);
  }
  ::close(ready[0]);
  return pid;
}

// The temporary files in `dir` that process `pid` wrote.
size_t temporariesOf(const fs::path& dir, pid_t pid) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    n += e.path().filename().string().find("-" + std::to_string(pid) + "-") != std::string::npos;
  return n;
}

// A process id no process has: the kernel hands out ids below pid_max, which can be raised to
// 2^22 and no further (PID_MAX_LIMIT). A dead child's own id is not that: the kernel may give it
// to another process (ids wrap at 32768 by default) before a write looks at its temporaries.
pid_t pidOfNoProcess() {
  const pid_t pid = pid_t{1} << 22;
  const int sent = ::kill(pid, 0), error = errno;
  EXPECT_EQ(sent, -1);
  EXPECT_EQ(error, ESRCH);
  return pid;
}

// Renames the temporary files in `dir` that process `from` wrote as if process `to` had.
void renameTemporaries(const fs::path& dir, pid_t from, pid_t to) {
  const std::string was = "-" + std::to_string(from) + "-", now = "-" + std::to_string(to) + "-";
  for (const auto& e : fs::directory_iterator(dir)) {
    std::string name = e.path().filename().string();
    const size_t at = name.find(was);
    if (name.rfind(".glint-tmp-", 0) != 0 || at == std::string::npos) continue;
    fs::rename(e.path(), dir / name.replace(at, was.size(), now));
  }
}

// The exit status of a child process (forked, so with this process's state) that writes `path`.
int exitOfChildWriting(const fs::path& path) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      writeTextFileAtomically(path.string(), "child");
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(AtomicFile, TemporariesOfKilledProcessesAreRemovedByTheNextWrite) {
  const fs::path dir = freshDir("stale");
  const pid_t killed = childInsideAWrite(dir, "frame.exr", /*die=*/true);
  ASSERT_EQ(temporaries(dir), 1u);  // what a killed process leaves
  ASSERT_EQ(temporariesOf(dir, killed), 1u);
  // Named for an id no process has, as the killed child's may be reused before the next write.
  const pid_t dead = pidOfNoProcess();
  renameTemporaries(dir, killed, dead);
  ASSERT_EQ(temporariesOf(dir, dead), 1u);
  // A second writer, which stops inside its write: its own write already removed the dead one's.
  const pid_t alive = childInsideAWrite(dir, "other.exr", /*die=*/false);
  ASSERT_GT(alive, 0);
  struct Reap {
    pid_t pid;
    ~Reap() {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  } reap{alive};
  EXPECT_EQ(temporariesOf(dir, dead), 0u);
  EXPECT_EQ(temporariesOf(dir, alive), 1u);
  // A live writer's temporary file is left alone …
  writeTextFileAtomically((dir / "next.json").string(), "next");
  EXPECT_EQ(temporariesOf(dir, alive), 1u);
  // … until it dies: then the next process to write there removes it.
  ::kill(alive, SIGKILL);
  ::waitpid(alive, nullptr, 0);
  renameTemporaries(dir, alive, dead);  // its id, too, may be reused
  EXPECT_EQ(exitOfChildWriting(dir / "next.json"), 0);
  EXPECT_EQ(temporaries(dir), 0u);
}

TEST(AtomicFile, ADirectoryIsCleanedOnceAProcessAndAgainByTheNext) {
  // A sequence's frames each read the directory of all the frames before them: a process
  // cleans a directory at its first write only. A temporary a process dies leaving after that
  // (here: made by name, for a process id no process has) is the next process's to remove.
  const fs::path dir = freshDir("once");
  writeTextFileAtomically((dir / "frame1.json").string(), "1");
  const pid_t gone = pidOfNoProcess();
  const std::string tag = [&] {
    // This host's tag, from the temporary a stopped writer leaves.
    const pid_t alive = childInsideAWrite(dir, "probe.exr", /*die=*/false);
    std::string t;
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (name.rfind(".glint-tmp-", 0) == 0) t = name.substr(11, 8);
    }
    ::kill(alive, SIGKILL);
    ::waitpid(alive, nullptr, 0);
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().find("probe") != std::string::npos) fs::remove(e.path());
    return t;
  }();
  ASSERT_EQ(tag.size(), 8u);
  const fs::path stale = dir / (".glint-tmp-" + tag + "-" + std::to_string(gone) + "-0-frame.exr");
  std::ofstream(stale) << "partial";
  writeTextFileAtomically((dir / "frame2.json").string(), "2");
  EXPECT_TRUE(fs::exists(stale));  // this process cleaned the directory already
  EXPECT_EQ(exitOfChildWriting(dir / "frame3.json"), 0);
  EXPECT_FALSE(fs::exists(stale));  // a new process's first write removed it
}

TEST(AtomicFile, DashWritesJsonToStandardOutput) {
  testing::internal::CaptureStdout();
  writeTextFileAtomically("-", "{\"a\": 1}\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "{\"a\": 1}\n");
}

mode_t modeOf(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

// Runs `body` in a child process as the unprivileged user nobody (65534) when this test runs as
// root, since root passes every permission check; as itself otherwise. Returns the error it
// threw ("" for none).
std::string asUnprivilegedUser(const std::function<void()>& body) {
  int pipe[2];
  if (::pipe(pipe) != 0) return "(no pipe)";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipe[0]);
    std::string message;
    if (::getuid() == 0 &&
        (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0))
      message = "(could not become nobody)";
    else
      try {
        body();
      } catch (const std::exception& e) {
        message = e.what();
      }
    (void)!::write(pipe[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(pipe[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(pipe[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, size_t(n));
  ::close(pipe[0]);
  ::waitpid(pid, nullptr, 0);
  return message;
}

TEST(AtomicFile, AReplacedFileKeepsItsMode) {
  const fs::path dir = freshDir("modes");
  const mode_t umaskWas = ::umask(022);
  for (const mode_t mode : {mode_t(0600), mode_t(0640), mode_t(0755)}) {
    const fs::path target = dir / ("frame-" + std::to_string(mode) + ".json");
    std::ofstream(target) << "old";
    ASSERT_EQ(::chmod(target.c_str(), mode), 0);
    writeTextFileAtomically(target.string(), "new");
    EXPECT_EQ(slurp(target), "new");
    // A rename puts the temporary file in its place: without keeping the mode, 0644 (umask 022).
    EXPECT_EQ(modeOf(target), mode) << std::oct << mode;
  }
  // A new file gets the writer's default, 0666 less the umask.
  writeTextFileAtomically((dir / "new.json").string(), "new");
  EXPECT_EQ(modeOf(dir / "new.json"), mode_t(0644));
  ::umask(umaskWas);
}

TEST(AtomicFile, AFileTheUserMayNotWriteIsNotReplaced) {
  // A 0444 file in a world-writable directory: the directory lets anyone rename over it, the
  // file's mode says this user may not write it (access(2), which root passes: root's own
  // writes replace it, keeping 0444, as its other writes to read-only files do).
  const fs::path dir = freshDir("read-only-file");
  ASSERT_EQ(::chmod(dir.c_str(), 0777), 0);
  const fs::path target = dir / "frame.json";
  std::ofstream(target) << "theirs";
  ASSERT_EQ(::chmod(target.c_str(), 0444), 0);
  const std::string refused =
      asUnprivilegedUser([&] { writeTextFileAtomically(target.string(), "mine"); });
  EXPECT_EQ(refused, "refusing to replace " + target.string() +
                         ": it is not writable by this user (mode 0444)");
  EXPECT_EQ(slurp(target), "theirs");
  EXPECT_EQ(temporaries(dir), 0u);
  if (::getuid() == 0) {
    writeTextFileAtomically(target.string(), "root's");
    EXPECT_EQ(slurp(target), "root's");
    EXPECT_EQ(modeOf(target), mode_t(0444));
  }
}

TEST(AtomicFile, ADirectoryNoFileCanBeMadeInIsFoundBeforeTheWrite) {
  // Checked as an unprivileged user (root may write a 0555 directory).
  const fs::path dir = freshDir("read-only-dir");
  ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
  const std::string target = (dir / "frame.exr").string();
  EXPECT_EQ(asUnprivilegedUser([&] { checkOutputPath(target); }),
            "cannot write " + target + ": no file can be made in " + dir.string() +
                " (Permission denied)");
  EXPECT_EQ(temporaries(dir), 0u);
  // A writable one passes, and the probe leaves nothing behind.
  const fs::path open = freshDir("writable-dir");
  ASSERT_EQ(::chmod(open.c_str(), 0777), 0);
  EXPECT_EQ(asUnprivilegedUser([&] { checkOutputPath((open / "frame.exr").string()); }), "");
  EXPECT_TRUE(fs::is_empty(open));
}

TEST(AtomicFile, TwoOutputsNamingOneFileAreRefused) {
  const fs::path dir = freshDir("two-outputs");
  const fs::path frame = dir / "x.exr", hard = dir / "hard.exr", soft = dir / "soft.json";
  std::ofstream(frame) << "frame";
  fs::create_hard_link(frame, hard);
  fs::create_symlink(frame, soft);
  fs::create_directory(dir / "sub");
  const auto refusal = [](const std::vector<NamedOutput>& outputs) {
    try {
      checkOutputPaths(outputs);
      return std::string("(accepted)");
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(refusal({{"-o", frame.string()}, {"--stats-json", frame.string()}}),
            "-o " + frame.string() + " and --stats-json " + frame.string() +
                " name one file: each output needs a file of its own");
  // Other names of one file: a hard link, a symbolic link, a path through "sub/..".
  EXPECT_NE(refusal({{"-o", frame.string()}, {"--display", hard.string()}}).find("name one file"),
            std::string::npos);
  EXPECT_NE(refusal({{"--json", soft.string()}, {"--diff", frame.string()}}).find("name one file"),
            std::string::npos);
  // Files that do not exist yet: the same path once made canonical.
  const std::string fresh = (dir / "p.json").string(),
                    alias = (dir / "sub" / ".." / "p.json").string();
  EXPECT_NE(refusal({{"--csv", fresh}, {"--json", ""}, {"--plot", alias}})
                .find("--csv " + fresh + " and --plot " + alias + " name one file"),
            std::string::npos);
  // Distinct files, outputs not asked for and standard output pass.
  EXPECT_EQ(refusal({{"--csv", fresh},
                     {"--json", "-"},
                     {"--plot", ""},
                     {"--diff", (dir / "q.png").string()}}),
            "(accepted)");
}

}  // namespace
}  // namespace glint
