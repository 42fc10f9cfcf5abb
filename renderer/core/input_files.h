#pragma once
// Every file Glint reads passes one check before anything opens it (checkInputFile): its name,
// its type, its size and its permissions. The files this run has read are remembered too: no
// output may replace one, so `glint render scene.json -o scene.json` is refused instead of
// destroying the scene.
#include <cstddef>
#include <cstdint>
#include <string>

#include <sys/types.h>

namespace glint {

// For checkInputFile: no limit on the size (the reader bounds what it allocates itself).
inline constexpr uint64_t kAnyFileSize = UINT64_MAX;

// Throws UsageError when `path` holds a NUL byte or another control character (bytes 1-31 and
// 127). Libraries open paths as C strings, so a name from a scene such as "h.ply\0.obj" passed
// a check of its extension as .obj while Assimp opened h.ply; names with other control
// characters are refused with it, since they would reach terminals in messages. `what` says
// what the path was given for ("mesh file").
void checkPathCharacters(const std::string& path, const std::string& what);

// `path` for a message: control characters written as \xNN, cut as excerpt() cuts.
std::string printablePath(const std::string& path);

// The check every input passes before it is read, in this order, so that nothing hostile is
// ever opened: the name (checkPathCharacters); the file exists (symbolic links followed); it
// is a regular file (a device such as /dev/zero never ends, and opening a FIFO waits for a
// writer); its size is at most `maxBytes` (stat's size: a sparse 3 GB file is refused unread);
// it can be opened for reading. Throws UsageError naming `what` and the file. Notes the file
// (below) and returns its size.
uint64_t checkInputFile(const std::string& path, uint64_t maxBytes, const std::string& what);

// What a file that is not a regular one is, for messages ("a FIFO"), from its st_mode.
const char* fileKind(mode_t mode);

// Remembers `path`'s file (by device and inode, so other names of it count too). Paths that
// cannot be stat'ed are ignored: reading them fails with its own error.
void noteInputFile(const std::string& path);

// Whether `path` names a file noted above.
bool isInputFile(const std::string& path);

// A file read on its own, outside a run (the Python module's read_frame and compare, in an
// interpreter that lives on): noted while it is read, as any input, and forgotten after unless
// something else had noted it (a scene's mesh), so that a later run may write it.
class InputReadAlone {
 public:
  explicit InputReadAlone(const std::string& path);
  ~InputReadAlone();
  InputReadAlone(const InputReadAlone&) = delete;
  InputReadAlone& operator=(const InputReadAlone&) = delete;

 private:
  std::string path_;
  bool wasNoted_ = true;
};

// Lets an output replace `path`'s file although it is read: the frame --resume continues, read
// whole before the render and written back under its own name.
void allowReplacingInput(const std::string& path);

// Reads a whole input file after checkInputFile's checks, and refuses more than `maxBytes`.
// Pipes and FIFOs are read too (a scene from `<(generator)`), up to `maxBytes`; a FIFO that
// nobody writes to reads as empty instead of waiting for a writer. Refused: a UsageError naming
// the file and `what` it was meant to be ("JSON scene"); a failure while reading: a GlintError.
std::string readInputFile(const std::string& path, size_t maxBytes, const std::string& what);

}  // namespace glint
