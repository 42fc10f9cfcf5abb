#pragma once
// Errors a user can act on. SceneError carries the file, line and JSON path of the mistake and
// formats as `scene.json:14: objects[3].radius: must be > 0, got -1`.
#include <stdexcept>
#include <string>
#include <string_view>

namespace glint {

class GlintError : public std::runtime_error {
 public:
  // A NUL in the message (a key or a name from hostile input) is written \x00: what() is read
  // as a C string, which ended there and hid the rest ("objects[0].bogus" without its reason).
  explicit GlintError(const std::string& message);
  explicit GlintError(const char* message) : std::runtime_error(message) {}
};

// Inputs that cannot work together (crops of different frames, a bad option combination):
// reported like scene errors, with exit code 2.
class UsageError : public GlintError {
 public:
  using GlintError::GlintError;
};

// The process ran out of memory, or a check found that what it is about to allocate will not
// fit (core/memory.h): a failure of the machine, not of the input, so exit code 1 (CLI.md). The
// message says what was being done ("out of memory while reading mesh big.obj"). Code that turns
// an input's GlintError into a scene error or a warning lets this one through.
class OutOfMemoryError : public GlintError {
 public:
  using GlintError::GlintError;
};

struct FileLoc {
  std::string file;  // as the user named it
  int line = 0;      // 1-based; 0 when unknown
};

class SceneError : public GlintError {
 public:
  SceneError(const FileLoc& loc, const std::string& path, const std::string& problem);
  const FileLoc& loc() const { return loc_; }
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  FileLoc loc_;
  std::string path_, problem_;
};

// Text from the input or from a library, for a message: beyond 200 bytes, its first 150 and last
// 50 ("head… (N characters) …tail", cut between UTF-8 characters), so that hostile input (a 10 MB
// enum value) cannot flood the terminal and a long library message keeps its reason, which comes
// last. inQuotes() adds the quotes.
std::string excerpt(const std::string& text);
std::string inQuotes(const std::string& value);

// Whether `text` is well-formed UTF-8 as far as sequence lengths go: every lead byte followed by
// the continuation bytes it announces, none standing alone.
bool isUtf8(std::string_view text);

// Edit distance, for "did you mean" suggestions on unknown keys and names.
size_t editDistance(const std::string& a, const std::string& b);

}  // namespace glint
