#include "io/mesh_limits.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "io/collada_limits.h"
#include "io/fbx_limits.h"
#include "io/obj_words.h"
#include "io/ply_header.h"
#include "io/scene_formats.h"

namespace glint {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string headOf(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  head.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

// Throws when a `v`, `vt` or `vn` line (`line`, number `lineNumber`) of OBJ file `mesh` holds a
// word that is not a decimal number as Assimp reads one (a comma may stand for the point), or
// one that is not a finite float (nan, inf, past float's range), or a count of numbers Assimp
// does not read as a vertex (x y z, x y z w, or x y z r g b), coordinate (u v, u v w) or normal
// (x y z). Assimp 5.2.5 read a texture coordinate's nan or 1e39 as 0 without a word (the
// image's corner), where Glint refuses the same values in a PLY file; it read "0x1p3" as 0,
// and a vertex of two numbers, or of words, it skipped, its faces then refused as "vertex index
// out of range".
void checkObjNumbers(const std::string& mesh, int lineNumber, std::string_view line) {
  const std::string_view keyword = takeObjWord(line);
  if (keyword != "v" && keyword != "vt" && keyword != "vn") return;
  const auto fail = [&](const std::string& why) {
    throw GlintError("mesh " + mesh + ":" + std::to_string(lineNumber) + ": " +
                     std::string(keyword) + " " + why);
  };
  int numbers = 0;
  for (std::string_view word = takeObjWord(line); !word.empty() && word[0] != '#';
       word = takeObjWord(line), ++numbers) {
    // Assimp counts a word as a number only where it starts with a digit or a sign (or is nan
    // or inf): ".5" made the vertex one number short, and it was skipped.
    if (word[0] == '.')
      fail("holds " + excerpt(std::string(word)) +
           ", which Assimp does not read as a number (write 0" + excerpt(std::string(word)) + ")");
    // As strtod reads it: from_chars takes no leading '+', and gives no value out of range. A
    // comma may stand for the point, as Assimp reads it (copied only then: files of 1 GiB).
    std::string withPoint;
    std::string_view digits = word[0] == '+' ? word.substr(1) : word;
    if (const size_t comma = digits.find(','); comma != std::string_view::npos) {
      withPoint = std::string(digits);
      withPoint[comma] = '.';
      digits = withPoint;
    }
    double v = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || end != digits.data() + digits.size() ||
        (error != std::errc() && error != std::errc::result_out_of_range))
      fail("holds " + excerpt(std::string(word)) + ", which is not a decimal number");
    if (error == std::errc::result_out_of_range)
      v = std::strtod(std::string(digits).c_str(), nullptr);
    if (!(std::fabs(v) <= std::numeric_limits<float>::max()))
      fail("holds " + excerpt(std::string(word)) + ", which is not a finite float");
  }
  const bool read = keyword == "v"    ? numbers == 3 || numbers == 4 || numbers == 6
                    : keyword == "vt" ? numbers == 2 || numbers == 3
                                      : numbers == 3;
  if (!read)
    fail("holds " + std::to_string(numbers) + (numbers == 1 ? " number" : " numbers") + "; " +
         (keyword == "v"    ? "a vertex is x y z, x y z w or x y z r g b"
          : keyword == "vt" ? "a texture coordinate is u v or u v w"
                            : "a normal is x y z"));
}

// The texture coordinates (vt) and normals (vn) an OBJ file's faces refer to, against those it
// has. Assimp 5.2.5 refuses a face's vertex index past the v lines, but reads a vt or vn index
// past its lines (or 0) as another vertex's or none, without a word: a wrong texture mapping.
struct ObjFaceReferences {
  static constexpr const char* kKinds[2] = {"vt", "vn"};
  int64_t lines[2] = {0, 0};     // vt and vn lines so far
  int64_t furthest[2] = {0, 0};  // the largest index a face gives, and its line
  int furthestLine[2] = {0, 0};

  void countVertexLine(std::string_view line) {
    const std::string_view word = takeObjWord(line, " \t\r");
    if (word == "vt") ++lines[0];
    if (word == "vn") ++lines[1];
  }

  // A face line's vt and vn indices: 1 to the lines in the file, or -1 back to minus the lines
  // before this one (negative indices count back from the line). Words that are not numbers
  // are Assimp's to judge.
  void checkFace(const std::string& mesh, int lineNumber, std::string_view line) {
    takeObjWord(line);  // "f"
    // Assimp takes a face of one or two vertices among triangles for a point or a line that its
    // own validation then refuses, naming no line. (It skips a face of none.)
    int vertices = 0;
    for (std::string_view words = line, w = takeObjWord(words); !w.empty() && w[0] != '#';
         w = takeObjWord(words))
      ++vertices;
    if (vertices == 1 || vertices == 2)
      throw GlintError("mesh " + mesh + ":" + std::to_string(lineNumber) + ": f gives " +
                       std::to_string(vertices) + (vertices == 1 ? " vertex" : " vertices") +
                       "; a face has at least 3 (a line is written l)");
    for (std::string_view word = takeObjWord(line); !word.empty() && word[0] != '#';
         word = takeObjWord(line)) {
      for (int k = -1; k < 2 && !word.empty(); ++k) {  // the vertex (k = -1), vt, vn
        const size_t slash = std::min(word.find('/'), word.size());
        const std::string_view index = word.substr(0, slash);
        word.remove_prefix(std::min(slash + 1, word.size()));
        int64_t i = 0;
        const auto [stop, error] = std::from_chars(index.data(), index.data() + index.size(), i);
        if (k < 0 || index.empty() || error != std::errc() || stop != index.data() + index.size())
          continue;
        const auto fail = [&](const std::string& why) {
          throw GlintError("mesh " + mesh + ":" + std::to_string(lineNumber) + ": a face gives " +
                           kKinds[k] + " index " + std::to_string(i) + ", " + why);
        };
        if (i == 0) fail("but OBJ indices start at 1");
        if (i < 0 && i < -lines[k])  // not -i: -2^63 has no negation
          fail("but only " + std::to_string(lines[k]) + " " + kKinds[k] + " lines come before it");
        if (i > furthest[k]) {
          furthest[k] = i;
          furthestLine[k] = lineNumber;
        }
      }
    }
  }

  // After the whole file: a positive index may name a line after its face, as Assimp reads it.
  void checkFurthest(const std::string& mesh) const {
    for (int k = 0; k < 2; ++k)
      if (furthest[k] > lines[k])
        throw GlintError("mesh " + mesh + ":" + std::to_string(furthestLine[k]) +
                         ": a face gives " + kKinds[k] + " index " + std::to_string(furthest[k]) +
                         ", but the file has " + std::to_string(lines[k]) + " " + kKinds[k] +
                         " lines");
  }
};

// The options of an MTL file's map lines that change where or how a map is read, which Assimp
// 5.2.5 parses and drops: "map_Kd -s 2 2 1 t.png" rendered the texture at scale 1 without a
// word. (-bm, a bump or normal map's scale, is applied.)
struct IgnoredMapOptions {
  std::vector<std::string> options;  // each once, in the order first given
  int firstLine = 0;

  void note(int lineNumber, std::string_view line) {
    static constexpr std::string_view kMaps[] = {"map_", "bump", "disp", "decal", "refl", "norm"};
    static constexpr std::string_view kIgnored[] = {"-s",      "-o",      "-t",      "-mm",
                                                    "-texres", "-clamp",  "-cc",     "-boost",
                                                    "-blendu", "-blendv", "-imfchan"};
    if (std::none_of(std::begin(kMaps), std::end(kMaps),
                     [&](std::string_view m) { return line.substr(0, m.size()) == m; }))
      return;
    constexpr const char* kSpace = " \t\r";
    takeObjWord(line, kSpace);  // the map's keyword
    for (std::string_view taken = takeObjWord(line, kSpace); !taken.empty();
         taken = takeObjWord(line, kSpace)) {
      const std::string word(taken);
      if (std::find(std::begin(kIgnored), std::end(kIgnored), word) == std::end(kIgnored) ||
          std::find(options.begin(), options.end(), word) != options.end())
        continue;
      options.push_back(word);
      if (firstLine == 0) firstLine = lineNumber;
    }
  }

  std::string list() const {
    std::string text;
    for (const std::string& o : options) text += (text.empty() ? "" : ", ") + o;
    return text;
  }
};

// Adds the names that follow `keyword` at the start of a line of `file` to `names`, and the
// material libraries its `mtllib` lines name to `libraries` (when given: `file` is the OBJ
// file itself, whose vertex lines are checked as well, checkObjNumbers, and its faces'
// references, ObjFaceReferences); throws past kMaxObjMaterials, naming `file`.
void collectObjNames(const std::string& mesh, const std::filesystem::path& file,
                     const char* keyword, std::set<std::string>& names,
                     std::vector<std::string>* libraries) {
  ObjFaceReferences references;
  IgnoredMapOptions ignoredMapOptions;  // of a material library
  std::ifstream in(file, std::ios::binary);
  // A keyword and the blank after it (Assimp takes a tab as a space).
  const auto startsWith = [](const std::string& line, size_t at, std::string_view word) {
    return line.compare(at, word.size(), word) == 0 && at + word.size() < line.size() &&
           (line[at + word.size()] == ' ' || line[at + word.size()] == '\t');
  };
  // A line that ends in '\\' goes on into the next, as Assimp reads an OBJ file; a joined line
  // is named by its first line's number.
  const auto continues = [](const std::string& line) {
    const size_t last = line.find_last_not_of(" \t\r");
    return last != std::string::npos && line[last] == '\\' ? last : std::string::npos;
  };
  int lineNumber = 0, linesRead = 0;
  for (std::string line; std::getline(in, line);) {
    lineNumber = ++linesRead;
    if (libraries)
      for (std::string next; continues(line) != std::string::npos && std::getline(in, next);) {
        ++linesRead;
        line.replace(continues(line), std::string::npos, " " + next);
      }
    size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos) continue;
    if (libraries && line[at] == 'v') {
      checkObjNumbers(mesh, lineNumber, line);
      references.countVertexLine(line);
    }
    if (libraries && line[at] == 'f' && at + 1 < line.size() &&
        (line[at + 1] == ' ' || line[at + 1] == '\t'))
      references.checkFace(mesh, lineNumber, std::string_view(line).substr(at));
    const auto rest = [&](size_t length) {
      std::string value = line.substr(std::min(line.size(), at + length));
      while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back())))
        value.pop_back();
      return value.substr(std::min(value.size(), value.find_first_not_of(" \t")));
    };
    if (startsWith(line, at, keyword)) {
      names.insert(rest(std::string_view(keyword).size() + 1));
      if (names.size() > kMaxObjMaterials)
        throw GlintError("mesh " + mesh +
                         (file == mesh ? "" : ": its material library " + file.string()) +
                         " names more than " + std::to_string(kMaxObjMaterials) + " materials (\"" +
                         keyword + "\" lines with distinct names); Glint reads at most " +
                         std::to_string(kMaxObjMaterials) + " from one OBJ file");
    } else if (libraries && startsWith(line, at, "mtllib")) {
      // Assimp opens and parses the library again for each line.
      if (libraries->size() == kMaxObjMaterials)
        throw GlintError("mesh " + mesh + ":" + std::to_string(lineNumber) + ": more than " +
                         std::to_string(kMaxObjMaterials) + " mtllib lines; Glint reads at most " +
                         std::to_string(kMaxObjMaterials) + " from one OBJ file");
      libraries->push_back(rest(7));
    } else if (!libraries) {
      ignoredMapOptions.note(lineNumber, std::string_view(line).substr(at));
    }
  }
  if (libraries) references.checkFurthest(mesh);
  if (!ignoredMapOptions.options.empty())
    log::warning("mesh " + mesh + ": its material library " + file.string() +
                 " gives map options " + ignoredMapOptions.list() + " (line " +
                 std::to_string(ignoredMapOptions.firstLine) +
                 " first), which Glint does not apply: its maps are read as if without them");
}

// The last `bytes` bytes of `path`.
std::string tailOf(const std::string& path, uint64_t size, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  const uint64_t from = size > bytes ? size - bytes : 0;
  in.seekg(static_cast<std::streamoff>(from));
  std::string tail(size - from, '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  tail.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return tail;
}

}  // namespace

void checkStlEnds(const std::string& path, uint64_t size) {
  const std::string head = headOf(path, 84);
  if (head.size() == 84) {
    const auto* b = reinterpret_cast<const unsigned char*>(head.data() + 80);
    const uint64_t faces = b[0] | uint64_t{b[1]} << 8 | uint64_t{b[2]} << 16 | uint64_t{b[3]} << 24;
    if (84 + 50 * faces == size) return;  // binary, whole (Assimp's test, before ASCII's)
  }
  const size_t start = head.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || lower(head.substr(start, 5)) != "solid") return;
  std::string tail = tailOf(path, size, 1024);
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
  const size_t lineStart = tail.find_last_of("\r\n");
  const std::string last = tail.substr(lineStart == std::string::npos ? 0 : lineStart + 1);
  const size_t word = last.find_first_not_of(" \t");
  if (word == std::string::npos || lower(last.substr(word, 8)) != "endsolid")
    throw GlintError("mesh " + path +
                     " is an ASCII STL file that does not end with an endsolid line (is it cut "
                     "short?); Assimp would read the facets before the cut without a word");
}

std::vector<std::string> objMaterialLibraries(const std::filesystem::path& dir,
                                              const std::string& value) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / value, ec)) return {value};
  std::vector<std::string> words;
  std::set<std::string> seen;  // a library named twice on a line is read once
  std::istringstream in(value);
  // One past the most checkObjFile takes, so that it can tell.
  for (std::string word; words.size() <= kMaxObjMaterials && in >> word;)
    if (seen.insert(word).second) words.push_back(word);
  return words.empty() ? std::vector<std::string>{value} : words;
}

void checkObjFile(const std::string& path) {
  std::set<std::string> used, defined;
  std::vector<std::string> libraries;
  collectObjNames(path, path, "usemtl", used, &libraries);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  // Each library once, however often it is named (a file of a million `mtllib a.mtl` lines
  // read a.mtl a million times), and the missing ones named up to a few.
  // Assimp reads a line's libraries anew for each line: the times they are named are bounded.
  std::set<std::string> named;
  size_t references = 0;
  for (const std::string& line : libraries)
    for (std::string& library : objMaterialLibraries(dir, line)) {
      named.insert(library);
      if (++references > kMaxObjMaterials)
        throw GlintError("mesh " + path + " names material libraries more than " +
                         std::to_string(kMaxObjMaterials) + " times; Glint reads at most " +
                         std::to_string(kMaxObjMaterials) + " from one OBJ file");
    }
  constexpr size_t kMissingNamed = 8;
  size_t missing = 0;
  for (const std::string& library : named) {
    std::error_code ec;
    const std::filesystem::path file = dir / library;
    // Assimp opens only regular files a mesh names (io/mesh_io.cpp); so does this count.
    if (std::filesystem::is_regular_file(file, ec))
      collectObjNames(path, file, "newmtl", defined, nullptr);
    else if (++missing <= kMissingNamed)
      log::warning("mesh " + path + ": its material library " + inQuotes(library) +
                   " is not a file beside it; its materials are left out");
  }
  if (missing > kMissingNamed)
    log::warning("mesh " + path + ": " + std::to_string(missing - kMissingNamed) +
                 " more material libraries it names are not files beside it");
  // Assimp gives a face of an undefined material its default grey without a word.
  for (const std::string& name : used)
    if (!defined.count(name))
      log::warning("mesh " + path + ": material " + inQuotes(name) +
                   " is used but no material library defines it; its faces get the default "
                   "material");
}

bool isMeshExtension(const std::string& extension) {
  const SceneFormat* f = findSceneFormat("x" + extension);
  return f && f->kind != SceneFileKind::GlintScene;
}

std::string meshFormatList() { return sceneFormatList(true); }

void checkPlyCounts(const std::string& path, const std::string& head, uint64_t fileSize) {
  if (head.size() < 3 || lower(head.substr(0, 3)) != "ply") return;  // the reader refuses it
  checkPlyElementsFitInTheFile(path, parsePlyHeader(path, head, fileSize), fileSize);
}

void checkMeshFileBeforeImport(const std::string& path) {
  const std::filesystem::path p(path);
  if (!isMeshExtension(p.extension().string()))
    throw GlintError("mesh " + path + ": Glint reads " + meshFormatList() + "; \"" +
                     excerpt(p.extension().string()) + "\" is not one of them");
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(p, ec);
  if (ec) throw GlintError("cannot read mesh " + path + ": " + ec.message());
  if (size > kMaxMeshFileBytes)
    throw GlintError("mesh " + path + " is " + std::to_string(size) +
                     " bytes; mesh files may have at most " + std::to_string(kMaxMeshFileBytes) +
                     " (1 GiB)");
  if (lower(p.extension().string()) == ".obj") checkObjFile(path);
  if (lower(p.extension().string()) == ".ply")
    checkPlyCounts(path, headOf(path, kMaxPlyHeaderBytes), size);
  if (lower(p.extension().string()) == ".dae") checkColladaCounts(path, headOf(path, size));
  if (lower(p.extension().string()) == ".stl") checkStlEnds(path, size);
  // A binary FBX file passes without being read whole.
  if (lower(p.extension().string()) == ".fbx" &&
      headOf(path, 18).rfind("Kaydara FBX Binary", 0) != 0)
    checkFbxEmbeddedContent(path, headOf(path, size));
}

}  // namespace glint
