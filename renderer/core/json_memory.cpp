#include "core/json_memory.h"

#include <algorithm>

#include "core/memory.h"

namespace glint {

namespace {

// nlohmann-json 3.11's allocations on 64-bit glibc, each with malloc's 16-byte header: bounds
// that JsonMemory.TheCountBoundsWhatNlohmannJsonTakes checks against the allocator's count.
// A value is 16 bytes in a vector, which grows to twice its size and holds its old buffer
// beside the new one as it grows: 48 bytes a value at that moment.
constexpr double kValue = 48;
constexpr double kArray = 48;   // the std::vector (24 bytes) a value points to
constexpr double kObject = 64;  // the std::map (48 bytes)
constexpr double kMember = 80;  // a map node: tree links (32) and the key (32); its value above
constexpr double kString = 48;  // the std::string (32 bytes)
// libstdc++ keeps up to 15 characters inside the string; longer ones take a buffer of their own.
double characterBytes(size_t length) { return length > 15 ? double(length + 1 + 16) : 0; }
// While a string is read the lexer holds it twice more (its token buffer, which grows by
// doubling, and the raw token kept for messages): four more copies of the longest, at most.
constexpr double kLongestStringCopies = 4;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool continuesScalar(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '.' ||
         c == '+' || c == '-';
}

}  // namespace

JsonTreeSize measureJsonTree(std::string_view text) {
  JsonTreeSize size;
  size_t longestString = 0;
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const char c = text[i];
    if (c == '\n' || c == '\r') ++size.lineEnds;
    if (c == '"') {
      const size_t begin = ++i;
      while (i < n && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
      const size_t length = std::min(i, n) - begin;  // escapes counted as written: an upper bound
      longestString = std::max(longestString, length);
      i = std::min(i + 1, n);
      size_t next = i;
      while (next < n && isSpace(text[next])) ++next;
      if (next < n && text[next] == ':') {
        size.bytes += kMember + characterBytes(length);
      } else {
        ++size.values;
        size.bytes += kValue + kString + characterBytes(length);
      }
    } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      const size_t end = std::min(text.find("*/", i + 2), n);
      size.lineEnds += size_t(std::count_if(text.begin() + i, text.begin() + end,
                                            [](char k) { return k == '\n' || k == '\r'; }));
      i = std::min(end + 2, n);
    } else if (c == '[' || c == '{') {
      ++size.values;
      size.bytes += kValue + (c == '[' ? kArray : kObject);
      ++i;
    } else if (continuesScalar(c)) {  // a number, true, false or null
      ++size.values;
      size.bytes += kValue;
      while (i < n && continuesScalar(text[i])) ++i;
    } else {
      ++i;
    }
  }
  size.bytes += kLongestStringCopies * double(longestString + 1);
  return size;
}

void checkJsonTreeFits(std::string_view text, double bytesPerValue, double bytesPerLine,
                       const std::string& what) {
  if (text.size() < (size_t{1} << 20)) return;
  const JsonTreeSize tree = measureJsonTree(text);
  checkMemoryFits(
      tree.bytes + bytesPerValue * double(tree.values) + bytesPerLine * double(tree.lineEnds),
      "parsing " + what + " (" + std::to_string(text.size()) + " bytes)");
}

}  // namespace glint
