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

}  // namespace

GlintError::GlintError(const std::string& message) : std::runtime_error(withNulsWritten(message)) {}

SceneError::SceneError(const FileLoc& loc, const std::string& path, const std::string& problem)
    : GlintError(formatSceneError(loc, path, problem)), loc_(loc), path_(path), problem_(problem) {}

std::string excerpt(const std::string& text) {
  constexpr size_t kMaxEchoed = 200;
  if (text.size() <= kMaxEchoed) return text;
  return text.substr(0, kMaxEchoed) + "… (" + std::to_string(text.size()) + " characters)";
}

std::string inQuotes(const std::string& value) { return "\"" + excerpt(value) + "\""; }

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
