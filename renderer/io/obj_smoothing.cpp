#include "io/obj_smoothing.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/memory.h"
#include "io/obj_words.h"

namespace glint {

namespace {

struct Normal {
  double x = 0, y = 0, z = 0;
  Normal& operator+=(const Normal& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  // Normalised; zero where it has no direction.
  Normal unit() const {
    const double length = std::sqrt(x * x + y * y + z * z);
    return length > 0 && std::isfinite(length) ? Normal{x / length, y / length, z / length}
                                               : Normal{};
  }
  bool isZero() const { return x == 0 && y == 0 && z == 0; }
};

struct Face {
  size_t line;         // which line of the file it is
  uint32_t group;      // 0: none
  size_t firstCorner;  // its corners' vertices in `corners`
  size_t cornerCount;
  Normal normal;     // Newell's: twice the face's area, along its normal
  size_t ownVn = 0;  // the vn line of its own normal, where a corner takes it
};

// Calls f(index, line) for each line of `text`, without its line end.
template <typename F>
void forEachLine(std::string_view text, F&& f) {
  size_t index = 0;
  for (size_t at = 0; at < text.size(); ++index) {
    const size_t end = std::min(text.find('\n', at), text.size());
    std::string_view line = text.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    f(index, line);
    at = end + 1;
  }
}

bool blankAt(std::string_view line, size_t at) {
  return at < line.size() && (line[at] == ' ' || line[at] == '\t');
}

// The group an `s` line puts the faces after it in: its name, empty for none (`s off`, `s 0`);
// nullopt for any other line.
std::optional<std::string_view> smoothingGroupOf(std::string_view line) {
  if (line.empty() || line[0] != 's' || !blankAt(line, 1)) return std::nullopt;
  std::string_view rest = line.substr(1);
  const std::string_view name = takeObjWord(rest);
  return name == "off" || name == "0" ? std::string_view() : name;
}

// x y z, x y z w (divided by w) or x y z r g b, as Assimp reads a vertex (a comma may stand for
// the point); nullopt for other counts, which Assimp skips (Glint's checks refuse them before:
// io/mesh_limits.h).
std::optional<Normal> vertexOf(std::string_view line) {
  double v[7];
  int n = 0;
  for (std::string_view word = takeObjWord(line); !word.empty() && word[0] != '#' && n < 7;
       word = takeObjWord(line)) {
    std::string number(word);
    std::replace(number.begin(), number.end(), ',', '.');
    v[n++] = std::strtod(number.c_str(), nullptr);
  }
  if (n == 4 && v[3] != 0) return Normal{v[0] / v[3], v[1] / v[3], v[2] / v[3]};
  if (n == 3 || n == 6) return Normal{v[0], v[1], v[2]};
  return std::nullopt;
}

// A face's vertex index as Assimp's face reader takes it whole: digits after an optional '-',
// the first not 0 (it reads "01" as two indices, 0 and 1, and "+1" as two as well).
std::optional<int64_t> faceIndex(std::string_view word) {
  const size_t digits = !word.empty() && word[0] == '-' ? 1 : 0;
  if (word.size() <= digits || word[digits] < '1' || word[digits] > '9') return std::nullopt;
  int64_t i = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), i);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return i;
}

std::string vnLine(const Normal& n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
  return buf;
}

}  // namespace

std::optional<std::string> objWithSmoothingGroupNormals(const std::string& text,
                                                        const std::string& path) {
  // What Assimp's reader reads: a line's first byte picks its kind (no blanks skipped).
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) return std::nullopt;
  bool grouped = false, unreadable = false;
  uint64_t vertices = 0, faceLines = 0, faceWords = 0;
  forEachLine(text, [&](size_t, std::string_view line) {
    const size_t last = line.find_last_not_of(" \t\v\f");
    if (line.rfind("vn", 0) == 0 || line.rfind("cstype", 0) == 0 ||
        (last != std::string_view::npos && line[last] == '\\'))
      unreadable = true;
    vertices += line.rfind('v', 0) == 0 && blankAt(line, 1);
    if (line.rfind('f', 0) == 0) {
      ++faceLines;
      std::string_view words = line.substr(1);
      while (!takeObjWord(words).empty()) ++faceWords;
    }
    if (const std::optional<std::string_view> name = smoothingGroupOf(line))
      grouped = grouped || !name->empty();
  });
  if (unreadable || !grouped) return std::nullopt;
  // Beside the text and its rewriting: each vertex's position, each face and its own normal's
  // line, and for each corner its vertex, its line, a group's normal (a map entry, the normal,
  // a vn line) and the index written after it.
  if (text.size() >= (size_t{1} << 20))
    checkMemoryFits(2.0 * double(text.size()) + 24.0 * double(vertices) +
                        112.0 * double(faceLines) + 160.0 * double(faceWords),
                    "giving mesh " + path + "'s smoothing groups their normals");

  std::vector<Normal> positions;
  std::vector<Face> faces;
  std::vector<uint32_t> corners;
  std::unordered_map<std::string_view, uint32_t> groupIds;  // "1", "12", ... → 1, 2, ...
  uint32_t group = 0;
  size_t textureLines = 0;
  forEachLine(text, [&](size_t index, std::string_view line) {
    if (unreadable || line.empty()) return;
    if (line[0] == 'v') {
      if (blankAt(line, 1)) {
        if (const std::optional<Normal> p = vertexOf(line.substr(1))) positions.push_back(*p);
      } else if (line.size() > 1 && line[1] == 't') {
        ++textureLines;
      }
    } else if (const std::optional<std::string_view> name = smoothingGroupOf(line)) {
      group = name->empty()
                  ? 0
                  : groupIds.try_emplace(*name, uint32_t(groupIds.size() + 1)).first->second;
    } else if (line[0] == 'f') {
      if (!blankAt(line, 1) || line.find('#') != std::string_view::npos) {
        unreadable = true;
        return;
      }
      Face face{index, group, corners.size(), 0, {}};
      std::string_view rest = line.substr(1);
      for (std::string_view word = takeObjWord(rest); !word.empty(); word = takeObjWord(rest)) {
        const size_t slash = word.find('/');
        const std::optional<int64_t> v = faceIndex(word.substr(0, slash));
        // With the vn lines written first, Assimp reads the texture index of a face before
        // any vt line as its normal's.
        const bool texture =
            slash != std::string_view::npos && slash + 1 < word.size() && word[slash + 1] != '/';
        // 1 to the vertices (a later line's too: Assimp checks at the end), or -1 back.
        const int64_t at = !v ? -1 : *v > 0 ? *v - 1 : int64_t(positions.size()) + *v;
        if (at < 0 || (texture && textureLines == 0)) {
          unreadable = true;
          return;
        }
        corners.push_back(uint32_t(std::min<int64_t>(at, UINT32_MAX)));
        ++face.cornerCount;
      }
      if (face.cornerCount > 0) faces.push_back(face);  // Assimp skips an empty face
    }
  });
  if (unreadable) return std::nullopt;
  for (Face& f : faces)
    for (size_t k = 0; k < f.cornerCount; ++k) {
      const uint32_t a = corners[f.firstCorner + k];
      const uint32_t b = corners[f.firstCorner + (k + 1) % f.cornerCount];
      if (a >= positions.size() || b >= positions.size()) return std::nullopt;
      const Normal& p = positions[a];
      const Normal& q = positions[b];
      f.normal +=
          Normal{(p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y)};
    }

  // Each group's normal at each of its vertices: the sum of its faces' there; vn line s + 1.
  std::unordered_map<uint64_t, size_t> smoothAt;  // group << 32 | vertex → index in `smooth`
  std::vector<Normal> smooth;
  const auto key = [&](const Face& f, size_t k) {
    return uint64_t(f.group) << 32 | corners[f.firstCorner + k];
  };
  for (const Face& f : faces) {
    if (f.group == 0) continue;
    for (size_t k = 0; k < f.cornerCount; ++k) {
      const auto [it, added] = smoothAt.try_emplace(key(f, k), smooth.size());
      if (added) smooth.emplace_back();
      smooth[it->second] += f.normal;
    }
  }
  for (Normal& n : smooth) n = n.unit();
  // Which corner takes which line: its group's normal, else its face's own, whose lines follow
  // the groups', one for each face that has a corner taking it.
  std::vector<size_t> cornerVn(corners.size());
  size_t ownLines = 0;
  for (Face& f : faces)
    for (size_t k = 0; k < f.cornerCount; ++k) {
      size_t& vn = cornerVn[f.firstCorner + k];
      if (f.group != 0) {
        const size_t s = smoothAt.at(key(f, k));
        if (!smooth[s].isZero()) {
          vn = s + 1;
          continue;
        }
      }
      if (f.ownVn == 0) f.ownVn = smooth.size() + ++ownLines;
      vn = f.ownVn;
    }

  std::string out;
  out.reserve(text.size() + 40 * (smooth.size() + ownLines) + 12 * corners.size());
  for (const Normal& n : smooth) out += vnLine(n);
  for (const Face& f : faces)
    if (f.ownVn != 0) out += vnLine(f.normal.unit());
  size_t nextFace = 0;
  forEachLine(text, [&](size_t index, std::string_view line) {
    if (nextFace == faces.size() || faces[nextFace].line != index) {
      out.append(line).append("\n");
      return;
    }
    const Face& f = faces[nextFace++];
    out += "f";
    std::string_view rest = line.substr(1);
    for (size_t k = 0; k < f.cornerCount; ++k) {
      const std::string_view word = takeObjWord(rest);
      const size_t slash = word.find('/');
      std::string_view texture;
      if (slash != std::string_view::npos) {
        texture = word.substr(slash + 1);
        texture = texture.substr(0, texture.find('/'));
      }
      out.append(" ").append(word.substr(0, slash)).append("/").append(texture).append("/");
      out += std::to_string(cornerVn[f.firstCorner + k]);
    }
    out += "\n";
  });
  return out;
}

}  // namespace glint
