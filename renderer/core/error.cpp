#include "core/error.h"

#include <algorithm>
#include <vector>

namespace glint {

namespace {

std::string withNulsWritten(const std::string& message) {
  if (message.find('\0') == std::string::npos) return message;
  std::string out;
  for (const char c : message) out += c == '\0' ? std::string("\\x00") : std::string(1, c);
  return out;
}

std::string formatSceneError(const FileLoc& loc, const std::string& path,
                             const std::string& problem) {
  std::string s = loc.file;
  if (loc.line > 0) s.append(":").append(std::to_string(loc.line));
  s.append(": ");
  if (!path.empty()) s.append(path).append(": ");
  return s.append(problem);
}

// Whether byte c continues a UTF-8 sequence (10xxxxxx): a cut there would split a character.
bool continuesCharacter(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

}  // namespace

GlintError::GlintError(const std::string& message) : std::runtime_error(withNulsWritten(message)) {}

SceneError::SceneError(const FileLoc& loc, const std::string& path, const std::string& problem)
    : GlintError(formatSceneError(loc, path, problem)), loc_(loc), path_(path), problem_(problem) {}

std::string excerpt(const std::string& text) {
  // The head names what failed; the tail is where libraries put why ("...: Length 2000000000").
  constexpr size_t kHead = 150, kTail = 50;
  if (text.size() <= kHead + kTail) return text;
  size_t headEnd = kHead, tailBegin = text.size() - kTail;
  while (headEnd > 0 && continuesCharacter(text[headEnd])) --headEnd;
  while (tailBegin < text.size() && continuesCharacter(text[tailBegin])) ++tailBegin;
  return text.substr(0, headEnd) + "… (" + std::to_string(text.size()) + " characters) …" +
         text.substr(tailBegin);
}

std::string inQuotes(const std::string& value) { return "\"" + excerpt(value) + "\""; }

bool isUtf8(std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const size_t length = c < 0x80           ? 1
                          : (c >> 5) == 0x6  ? 2
                          : (c >> 4) == 0xe  ? 3
                          : (c >> 3) == 0x1e ? 4
                                             : 0;
    if (length == 0 || i + length > text.size()) return false;
    for (size_t k = 1; k < length; ++k)
      if (!continuesCharacter(text[i + k])) return false;
    i += length;
  }
  return true;
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace glint
