// Outputs never destroy what they must not: what is not a regular file, the run's inputs, or the
// previous file when the write fails; temporary names fit NAME_MAX and do not outlive a kill.
#include "film/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
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

TEST(AtomicFile, TemporariesOfKilledProcessesAreRemovedByTheNextWrite) {
  const fs::path dir = freshDir("stale");
  const pid_t dead = childInsideAWrite(dir, "frame.exr", /*die=*/true);
  ASSERT_EQ(temporaries(dir), 1u);  // what a killed process leaves
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
  // … until it dies.
  ::kill(alive, SIGKILL);
  ::waitpid(alive, nullptr, 0);
  writeTextFileAtomically((dir / "next.json").string(), "again");
  EXPECT_EQ(temporaries(dir), 0u);
}

TEST(AtomicFile, DashWritesJsonToStandardOutput) {
  testing::internal::CaptureStdout();
  writeTextFileAtomically("-", "{\"a\": 1}\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "{\"a\": 1}\n");
}

}  // namespace
}  // namespace glint
