#include "app/farm_plan.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include "core/error.h"

namespace glint {

std::vector<PixelWindow> farmTiles(int width, int height, int count, int* columnsOut,
                                   int* rowsOut) {
  if (count < 1) throw UsageError("--tiles must be at least 1, got " + std::to_string(count));
  // Square tiles keep a tile's share of the scene (and of its cost) close to its share of
  // the pixels, and keep the crop edges, which every task pays for in BVH traversal, short.
  int columns = 0, rows = 0;
  double best = 0;
  for (int c = 1; c <= count; ++c) {
    if (count % c != 0) continue;
    const int r = count / c;
    if (c > width || r > height) continue;
    const double cost = std::abs(std::log((double(width) / c) / (double(height) / r)));
    if (columns == 0 || cost < best) columns = c, rows = r, best = cost;
  }
  if (columns == 0)
    throw UsageError(std::to_string(count) + " tiles do not fit a " + std::to_string(width) + "x" +
                     std::to_string(height) + " frame as a grid of non-empty tiles");
  if (columnsOut) *columnsOut = columns;
  if (rowsOut) *rowsOut = rows;
  // 64-bit products: i · W overflows int for 32768-pixel frames cut into many tiles.
  const auto edge = [](int i, int size, int parts) {
    return int(int64_t(i) * int64_t(size) / int64_t(parts));
  };
  std::vector<PixelWindow> tiles;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      tiles.push_back({edge(i, width, columns), edge(i + 1, width, columns), edge(j, height, rows),
                       edge(j + 1, height, rows)});
  return tiles;
}

namespace {

bool parseFrame(std::string_view s, int& out) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size() && out >= 0;
}

}  // namespace

FrameRange parseFrameRange(const std::string& text, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    return UsageError(what + ": " + why + ", got " + inQuotes(text) + " (write A-B or A)");
  };
  const size_t dash = text.find('-');
  FrameRange r;
  if (dash == std::string::npos) {
    if (!parseFrame(text, r.first)) throw bad("frames are non-negative integers");
    r.last = r.first;
    return r;
  }
  if (!parseFrame(std::string_view(text).substr(0, dash), r.first) ||
      !parseFrame(std::string_view(text).substr(dash + 1), r.last))
    throw bad("frames are non-negative integers");
  if (r.first > r.last) throw bad("the first frame must not come after the last");
  return r;
}

namespace {

// Where the frame number goes in the file name (not the directories): the last run of '#', or
// else the last printf-style "%d" / "%0Nd", read as printf reads them: "%%" is a literal '%'
// (so "%%d" is not a field), and a '%' that starts no conversion stays as written. npos when
// there is neither.
struct FrameField {
  size_t begin = std::string::npos, end = 0, width = 0;
  size_t nameBegin = 0;
  bool printf = false;  // the name's "%%" then stand for '%'
};

FrameField frameField(const std::string& pattern) {
  const size_t slash = pattern.find_last_of('/');
  const size_t nameBegin = slash == std::string::npos ? 0 : slash + 1;
  FrameField f;
  f.nameBegin = nameBegin;
  const size_t hash = pattern.find_last_of('#');
  if (hash != std::string::npos && hash >= nameBegin) {
    f.end = hash + 1;
    f.begin = hash;
    while (f.begin > nameBegin && pattern[f.begin - 1] == '#') --f.begin;
    f.width = f.end - f.begin;
    return f;
  }
  for (size_t at = nameBegin; at < pattern.size(); ++at) {
    if (pattern[at] != '%') continue;
    if (at + 1 < pattern.size() && pattern[at + 1] == '%') {
      ++at;
      continue;
    }
    size_t i = at + 1, width = 0;
    if (i < pattern.size() && pattern[i] == '0') ++i;
    for (; i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])); ++i)
      width = std::min<size_t>(width * 10 + size_t(pattern[i] - '0'), 32);
    if (i < pattern.size() && pattern[i] == 'd') {
      f = {at, i + 1, width, nameBegin, true};
      at = i;
    }
  }
  return f;
}

// `text` with each "%%" written as '%'.
std::string percentsUnescaped(std::string_view text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '%' && i + 1 < text.size() && text[i + 1] == '%') ++i;
  }
  return out;
}

}  // namespace

bool hasFrameDigits(const std::string& pattern) {
  return frameField(pattern).begin != std::string::npos;
}

std::string frameFileName(const std::string& pattern, int frame) {
  const FrameField f = frameField(pattern);
  if (f.begin == std::string::npos) return pattern;
  std::string digits = std::to_string(frame);
  if (digits.size() < f.width) digits.insert(0, f.width - digits.size(), '0');
  if (!f.printf) return pattern.substr(0, f.begin) + digits + pattern.substr(f.end);
  const std::string_view all(pattern);
  return pattern.substr(0, f.nameBegin) +
         percentsUnescaped(all.substr(f.nameBegin, f.begin - f.nameBegin)) + digits +
         percentsUnescaped(all.substr(f.end));
}

}  // namespace glint
