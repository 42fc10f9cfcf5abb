#include "io/collada_limits.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "core/error.h"

namespace glint {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

class Scanner {
 public:
  Scanner(const std::string& path, std::string_view bytes) : path_(path), b_(bytes) {}

  void run() {
    while ((at_ = b_.find('<', at_)) != std::string_view::npos) {
      if (skip("<!--", "-->") || skip("<![CDATA[", "]]>") || skip("<?", "?>") || skip("<!", ">") ||
          skip("</", ">"))
        continue;
      element();
    }
  }

 private:
  [[noreturn]] void fail(size_t pos, const std::string& what) const {
    const size_t line = size_t(std::count(b_.begin(), b_.begin() + ptrdiff_t(pos), '\n')) + 1;
    throw GlintError("mesh " + path_ + ":" + std::to_string(line) + ": " + what);
  }

  // Skips a construct that starts with `open` at at_, through `close` (or to the end).
  bool skip(std::string_view open, std::string_view close) {
    if (b_.compare(at_, open.size(), open) != 0) return false;
    const size_t end = b_.find(close, at_ + open.size());
    at_ = end == std::string_view::npos ? b_.size() : end + close.size();
    return true;
  }

  // A start tag at at_: its count and stride attributes, then the content of <p> and <vcount>.
  void element() {
    size_t i = at_ + 1;
    const size_t nameStart = i;
    while (i < b_.size() && !isSpace(b_[i]) && b_[i] != '>' && b_[i] != '/') ++i;
    const std::string_view name = b_.substr(nameStart, i - nameStart);
    bool selfClosing = false;
    while (i < b_.size() && b_[i] != '>') {
      if (b_[i] == '/') selfClosing = true;
      if (isSpace(b_[i]) || b_[i] == '/') {
        ++i;
        continue;
      }
      selfClosing = false;
      const size_t keyStart = i;
      while (i < b_.size() && b_[i] != '=' && !isSpace(b_[i]) && b_[i] != '>') ++i;
      const std::string_view key = b_.substr(keyStart, i - keyStart);
      while (i < b_.size() && isSpace(b_[i])) ++i;
      if (i >= b_.size() || b_[i] != '=') continue;
      ++i;
      while (i < b_.size() && isSpace(b_[i])) ++i;
      if (i >= b_.size() || (b_[i] != '"' && b_[i] != '\'')) continue;
      const char quote = b_[i++];
      const size_t end = std::min(b_.find(quote, i), b_.size());
      if (key == "count" || key == "stride") attributeCount(keyStart, key, b_.substr(i, end - i));
      i = end + 1;
    }
    at_ = std::min(i + 1, b_.size());
    if (selfClosing || (name != "p" && name != "vcount")) return;
    const size_t end = std::min(b_.find('<', at_), b_.size());
    if (end == b_.size())
      fail(end, "the file ends inside a <" + std::string(name) + "> (is it cut short?)");
    if (b_.compare(end, name.size() + 2, "</" + std::string(name)) != 0)
      fail(end, "<" + std::string(name) + "> holds markup; Glint reads its whole numbers only");
    uint64_t sum = 0;
    for (size_t k = at_; k < end; ++k) {
      const char c = b_[k];
      if (isDigit(c) || isSpace(c) || (name == "p" && (c == '-' || c == '+'))) continue;
      char shown[16];
      std::snprintf(shown, sizeof shown, c > ' ' && c < 127 ? "\"%c\"" : "byte 0x%02x",
                    static_cast<unsigned char>(c));
      fail(k, "<" + std::string(name) + "> holds " + shown +
                  "; Collada's index lists hold whole numbers and white space only (Assimp's "
                  "reader never ended on other characters)");
    }
    if (name == "vcount")
      for (size_t k = at_; k < end;) {
        uint64_t v = 0;
        for (; k < end && isDigit(b_[k]); ++k)
          v = std::min<uint64_t>(v * 10 + (b_[k] - '0'), b_.size() + 1);
        sum = std::min<uint64_t>(sum + v, b_.size() + 1);
        while (k < end && !isDigit(b_[k])) ++k;
      }
    if (sum > b_.size())
      fail(at_, "<vcount> gives polygons of more vertices in all than the file's " +
                    std::to_string(b_.size()) + " bytes can index");
    at_ = end;
  }

  void attributeCount(size_t pos, std::string_view key, std::string_view value) const {
    const size_t first = value.find_first_not_of(" \t\r\n");
    const size_t last = value.find_last_not_of(" \t\r\n");
    const std::string_view digits = first == std::string_view::npos
                                        ? value.substr(0, 0)
                                        : value.substr(first, last - first + 1);
    uint64_t v = 0;
    bool whole = !digits.empty();
    for (const char c : digits) {
      if (!isDigit(c)) {
        whole = false;
        break;
      }
      v = std::min<uint64_t>(v * 10 + uint64_t(c - '0'), b_.size() + 1);
    }
    if (!whole)
      fail(pos, std::string(key) + "=" + inQuotes(excerpt(std::string(value))) +
                    " is not a whole number");
    if (v > b_.size())
      fail(pos, std::string(key) + "=\"" + std::string(digits) + "\" is more than the file's " +
                    std::to_string(b_.size()) + " bytes can hold");
  }

  const std::string& path_;
  std::string_view b_;
  size_t at_ = 0;
};

}  // namespace

void checkColladaCounts(const std::string& path, const std::string& bytes) {
  Scanner(path, bytes).run();
}

}  // namespace glint
