#include "io/fbx_limits.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string_view>

#include "core/error.h"

namespace glint {

namespace {

bool isBase64Letter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' ||
         c == '/';
}

// What is wrong with `text` as one base64 string, or "" when nothing is.
std::string base64Fault(std::string_view text) {
  size_t padding = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '=') {
      ++padding;
      continue;
    }
    if (isBase64Letter(c) && padding == 0) continue;
    char shown[16];
    std::snprintf(shown, sizeof shown, c > ' ' && c < 127 ? "\"%c\"" : "byte 0x%02x",
                  static_cast<unsigned char>(c));
    return padding > 0 ? "has " + std::string(shown) + " after its padding '='"
                       : "has " + std::string(shown) + " at character " + std::to_string(i + 1) +
                             ", outside base64's alphabet";
  }
  if (padding > 2)
    return "ends in " + std::to_string(padding) + " '=' (base64 pads with 2 at most)";
  if (text.size() % 4 != 0)
    return "is " + std::to_string(text.size()) + " characters long, not a multiple of 4";
  return "";
}

}  // namespace

void checkFbxEmbeddedContent(const std::string& path, const std::string& bytes) {
  if (bytes.rfind("Kaydara FBX Binary", 0) == 0) return;
  const std::string_view b(bytes);
  const auto fail = [&](size_t at, const std::string& what) {
    const size_t line = 1 + size_t(std::count(b.begin(), b.begin() + std::ptrdiff_t(at), '\n'));
    throw GlintError("mesh " + path + ":" + std::to_string(line) + ": its embedded texture " +
                     "(Content) " + what);
  };
  constexpr std::string_view kKey = "Content:";
  for (size_t key = b.find(kKey); key != std::string_view::npos; key = b.find(kKey, key + 1)) {
    // The property's key begins its line.
    const size_t lineStart = b.find_last_of('\n', key == 0 ? 0 : key - 1);
    const size_t from = lineStart == std::string_view::npos || key == 0 ? 0 : lineStart + 1;
    if (b.substr(from, key - from).find_first_not_of(" \t") != std::string_view::npos) continue;
    // Its values: quoted strings, separated by commas and white space.
    for (size_t at = key + kKey.size(); at < b.size();) {
      const char c = b[at];
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',') {
        ++at;
        continue;
      }
      if (c != '"') break;
      const size_t end = b.find('"', at + 1);
      if (end == std::string_view::npos) fail(at, "has a string that is never closed");
      if (const std::string fault = base64Fault(b.substr(at + 1, end - at - 1)); !fault.empty())
        fail(at, "is not base64: its string " + fault);
      at = end + 1;
    }
  }
}

}  // namespace glint
