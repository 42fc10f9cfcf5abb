// The one check every input file passes before it is read (core/input_files.h). Tests that make
// a FIFO bound themselves with alarm(): a check that opened one for reading would wait for a
// writer for ever, and the alarm ends the test binary instead.
#include "core/input_files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "test_util.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string refusal(const std::string& path, uint64_t maxBytes = 1 << 20) {
  try {
    checkInputFile(path, maxBytes, "mesh file");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(accepted)";
}

struct Alarm {
  explicit Alarm(unsigned seconds) { ::alarm(seconds); }
  ~Alarm() { ::alarm(0); }
};

fs::path freshDir(const char* name) {
  const fs::path dir = test::tempDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(InputFiles, APathWithAControlCharacterIsRefusedByItsByte) {
  // "h.ply\0.obj": the extension says .obj, a C string opens h.ply. The file h.ply exists, so
  // only the name can refuse it.
  const fs::path dir = freshDir("nul");
  std::ofstream(dir / "h.ply") << "ply\n";
  const std::string nul = (dir / "h.ply").string() + std::string(1, '\0') + ".obj";
  const std::string message = refusal(nul);
  EXPECT_NE(message.find("has \\x00 (NUL) at byte " + std::to_string(nul.find('\0'))),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("h.ply\\x00.obj"), std::string::npos) << message;  // shown escaped
  // A newline or an escape (terminal control) likewise; byte 0x7f (DEL) too.
  for (const char c : {'\n', '\x1b', '\x7f'}) {
    EXPECT_THROW(checkPathCharacters(std::string("a") + c + "b.obj", "mesh file"), UsageError);
  }
  EXPECT_NO_THROW(checkPathCharacters("été/b c.obj", "mesh file"));  // UTF-8 and spaces pass
}

TEST(InputFiles, OnlyRegularFilesAreRead) {
  const Alarm bound(20);
  const fs::path dir = freshDir("kinds");
  ASSERT_EQ(::mkfifo((dir / "f.gltf").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "z.gltf");
  fs::create_directories(dir / "d.gltf");
  EXPECT_EQ(refusal((dir / "f.gltf").string()),
            "mesh file " + (dir / "f.gltf").string() + " is a FIFO; it must be a regular file");
  // The link is followed: what is read is what it names.
  EXPECT_EQ(refusal((dir / "z.gltf").string()), "mesh file " + (dir / "z.gltf").string() +
                                                    " is a character device; it must be a "
                                                    "regular file");
  EXPECT_NE(refusal((dir / "d.gltf").string()).find("is a directory"), std::string::npos);
  EXPECT_EQ(refusal((dir / "none.gltf").string()),
            "mesh file not found: " + (dir / "none.gltf").string());
}

TEST(InputFiles, TheSizeIsCheckedBeforeAnythingIsRead) {
  // A sparse file of 3 GB: stat says its size, no byte of it is read.
  const fs::path big = freshDir("size") / "big.gltf";
  std::ofstream(big) << "{}";
  fs::resize_file(big, uint64_t{3} << 30);
  EXPECT_EQ(refusal(big.string(), uint64_t{1} << 30),
            "mesh file " + big.string() + " is 3221225472 bytes; the limit is 1024 MiB");
  // At the limit exactly it passes, and its size comes back.
  EXPECT_EQ(checkInputFile(big.string(), uint64_t{3} << 30, "mesh file"), uint64_t{3} << 30);
  fs::remove(big);
}

TEST(InputFiles, AnUnreadableFileIsNamed) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads files whatever their mode";
  const fs::path file = freshDir("mode") / "secret.obj";
  std::ofstream(file) << "v 0 0 0\n";
  fs::permissions(file, fs::perms::none);
  EXPECT_EQ(refusal(file.string()),
            "cannot read mesh file " + file.string() + ": Permission denied");
}

TEST(InputFiles, ScenesAreReadFromPipesButAFifoNobodyWritesToIsNotWaitedFor) {
  const Alarm bound(20);
  const fs::path dir = freshDir("pipes");
  const std::string fifo = (dir / "s.json").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    readInputFile(fifo, 1 << 20, "JSON scene");
    ADD_FAILURE() << "a FIFO nobody wrote to was read";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "JSON scene " + fifo + " is a FIFO or pipe that nobody wrote to");
  }
  // A pipe's bytes are the scene (`glint render <(generator)` opens /dev/fd/N): here one whose
  // writer has written and closed its end.
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  const std::string scene = "{\"objects\": []}";
  ASSERT_EQ(::write(ends[1], scene.data(), scene.size()), ssize_t(scene.size()));
  ::close(ends[1]);
  EXPECT_EQ(readInputFile("/proc/self/fd/" + std::to_string(ends[0]), 1 << 20, "JSON scene"),
            scene);
  ::close(ends[0]);
  // A device is not a pipe: /dev/zero is refused at once, not read to the limit.
  try {
    readInputFile("/dev/zero", 1 << 20, "JSON scene");
    ADD_FAILURE() << "/dev/zero was read";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "JSON scene /dev/zero is a character device; it must be a regular file or a pipe");
  }
}

}  // namespace
}  // namespace glint
