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
  size_t line = 1;
  const auto fail = [&](const std::string& what) {
    throw GlintError("mesh " + path + ":" + std::to_string(line) + ": its embedded texture " +
                     "(Content) " + what);
  };
  // The file's tokens as Assimp's ASCII tokenizer cuts them: ';' comments to the line's end,
  // quoted strings, the separators , { } and :, and runs of other characters; a token followed
  // by ':' is a key. Content's values are the tokens after its key up to the next key or brace.
  bool inContent = false;
  for (size_t at = 0; at < b.size();) {
    const char c = b[at];
    if (c == '\n') ++line;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',') {
      ++at;
      continue;
    }
    if (c == ';') {
      at = std::min(b.find('\n', at), b.size());
      continue;
    }
    if (c == '{' || c == '}' || c == ':') {
      inContent = inContent && c == ':';  // a key's colon; a brace ends its values
      ++at;
      continue;
    }
    size_t end;
    if (c == '"') {
      end = b.find('"', at + 1);
      if (end == std::string_view::npos) {
        if (inContent) fail("has a string that is never closed");
        return;  // Assimp's tokenizer refuses the file itself
      }
      ++end;
    } else {
      end = b.find_first_of(" \t\r\n,{}:;\"", at);
      if (end == std::string_view::npos) end = b.size();
    }
    const std::string_view token = b.substr(at, end - at);
    const size_t next = b.find_first_not_of(" \t\r", end);
    const bool key = next != std::string_view::npos && b[next] == ':';
    if (key) {
      inContent = token == "Content";
    } else if (inContent) {
      if (token.size() < 2 || token.front() != '"')
        fail("is not base64: " + inQuotes(std::string(token.substr(0, 16))) +
             " is not a quoted string");
      if (const std::string fault = base64Fault(token.substr(1, token.size() - 2)); !fault.empty())
        fail("is not base64: its string " + fault);
    }
    line += size_t(std::count(token.begin(), token.end(), '\n'));
    at = end;
  }
}

}  // namespace glint
