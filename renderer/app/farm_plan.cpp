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

// Where the file name (not the directories) begins.
size_t nameBegin(const std::string& pattern) {
  const size_t slash = pattern.find_last_of('/');
  return slash == std::string::npos ? 0 : slash + 1;
}

// The last run of '#' in the file name: [begin, end), or begin = npos where there is none.
struct HashRun {
  size_t begin = std::string::npos, end = 0;
};

HashRun hashRun(const std::string& pattern) {
  HashRun run;
  const size_t hash = pattern.find_last_of('#');
  if (hash == std::string::npos || hash < nameBegin(pattern)) return run;
  run.end = hash + 1;
  run.begin = hash;
  while (run.begin > nameBegin(pattern) && pattern[run.begin - 1] == '#') --run.begin;
  return run;
}

// `frame` written in at least `width` digits, zero-padded.
std::string padded(int frame, size_t width) {
  std::string digits = std::to_string(frame);
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return digits;
}

// `name` as printf formats it with `frame` for each "%d" and "%0Nd" (N capped at 32): "%%" is a
// literal '%' (so "%%d" is no field), and a '%' that starts no conversion stays as written.
// False where the name has no field.
bool printfName(std::string_view name, int frame, std::string& out) {
  bool any = false;
  for (size_t at = 0; at < name.size(); ++at) {
    if (name[at] != '%') {
      out += name[at];
      continue;
    }
    if (at + 1 < name.size() && name[at + 1] == '%') {
      out += '%';
      ++at;
      continue;
    }
    size_t i = at + 1, width = 0;
    if (i < name.size() && name[i] == '0') ++i;
    for (; i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])); ++i)
      width = std::min<size_t>(width * 10 + size_t(name[i] - '0'), 32);
    if (i < name.size() && name[i] == 'd') {
      out += padded(frame, width);
      at = i;
      any = true;
    } else {
      out += '%';
    }
  }
  return any;
}

}  // namespace

bool hasFrameDigits(const std::string& pattern) {
  std::string unused;
  return hashRun(pattern).begin != std::string::npos ||
         printfName(std::string_view(pattern).substr(nameBegin(pattern)), 0, unused);
}

std::string frameFileName(const std::string& pattern, int frame) {
  if (const HashRun run = hashRun(pattern); run.begin != std::string::npos)
    return pattern.substr(0, run.begin) + padded(frame, run.end - run.begin) +
           pattern.substr(run.end);
  std::string name = pattern.substr(0, nameBegin(pattern));
  if (!printfName(std::string_view(pattern).substr(nameBegin(pattern)), frame, name))
    return pattern;
  return name;
}

}  // namespace glint
