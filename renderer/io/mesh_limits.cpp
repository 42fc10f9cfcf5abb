#include "io/mesh_limits.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace glint {

namespace {

// A PLY header longer than this (comments, mostly) is refused rather than read on.
constexpr size_t kMaxPlyHeaderBytes = size_t{1} << 20;

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

// The least bytes a value of a PLY scalar type takes in a binary file; unknown types 1.
uint64_t binarySize(const std::string& type) {
  static const std::pair<const char*, uint64_t> kSizes[] = {
      {"char", 1},   {"int8", 1},    {"uchar", 1},  {"uint8", 1},  {"short", 2}, {"int16", 2},
      {"ushort", 2}, {"uint16", 2},  {"int", 4},    {"int32", 4},  {"uint", 4},  {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, size] : kSizes)
    if (type == name) return size;
  return 1;
}

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  // Per property, the type its binary size counts: a scalar's own, or a list's count type (an
  // empty list is its count alone).
  std::vector<std::string> sizeTypes;
};

// Assimp ends a header line at '\r', '\n' or NUL, so a line hidden after a lone '\r' in a
// comment counts as its own line here too.
std::vector<std::string> headerLines(const std::string& head, size_t* bodyStart) {
  std::vector<std::string> lines;
  size_t at = 0;
  *bodyStart = std::string::npos;
  while (at < head.size()) {
    size_t end = head.find_first_of(std::string("\r\n\0", 3), at);
    if (end == std::string::npos) end = head.size();
    lines.push_back(head.substr(at, end - at));
    at = end + 1;
    if (end < head.size() && head[end] == '\r' && at < head.size() && head[at] == '\n')
      ++at;  // \r\n is one line end
    std::istringstream first(lines.back());
    std::string token;
    if (first >> token && token == "end_header") {
      *bodyStart = std::min(at, head.size());
      break;
    }
  }
  return lines;
}

}  // namespace

bool isMeshExtension(const std::string& extension) {
  const std::string e = lower(extension);
  return e == ".obj" || e == ".ply" || e == ".gltf" || e == ".glb";
}

const char* meshFormatList() { return "OBJ (.obj), PLY (.ply) and glTF 2.0 (.gltf, .glb)"; }

void checkPlyCounts(const std::string& path, const std::string& head, uint64_t fileSize) {
  if (head.size() < 3 || lower(head.substr(0, 3)) != "ply") return;  // Assimp refuses it
  size_t bodyStart = 0;
  const std::vector<std::string> lines = headerLines(head, &bodyStart);
  // Assimp 5.2's PLY reader loops forever on a header that never ends (even a four-line file).
  if (bodyStart == std::string::npos)
    throw GlintError("mesh " + path + ": its PLY header has no end_header line" +
                     (head.size() < fileSize
                          ? " in its first " + std::to_string(kMaxPlyHeaderBytes) + " bytes"
                          : std::string()));
  enum class Format { Ascii, Binary } format = Format::Binary;
  std::vector<PlyElement> elements;
  // The header's lines must be PLY 1.0's as its specification writes them (one "ply", one
  // format line, elements with a count, properties of known types): Assimp 5.2's reader never
  // returned from a binary file whose header repeated and garbled them (a 190-byte file, found
  // by glint_fuzz_mesh), so anything else is refused before Assimp sees it.
  const auto refuse = [&](const std::string& line, const char* why) {
    throw GlintError("mesh " + path + ": its PLY header line \"" + excerpt(line) + "\" " + why);
  };
  const auto isCount = [](const std::string& t) {
    return !t.empty() && t.size() <= 20 &&
           std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c); });
  };
  const auto isType = [](const std::string& t) {
    return binarySize(t) > 1 || t == "char" || t == "int8" || t == "uchar" || t == "uint8";
  };
  int formats = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string w; tokens >> w;) words.push_back(w);
    const std::string keyword = words.empty() ? std::string() : words[0];
    if (i == 0) {
      if (words.size() != 1 || keyword != "ply") refuse(line, "should be \"ply\" alone");
      continue;
    }
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info" || keyword == "end_header")
      continue;
    if (keyword == "format") {
      if (++formats > 1) refuse(line, "is a second format line");
      if (words.size() != 3 || words[2] != "1.0" ||
          (words[1] != "ascii" && words[1] != "binary_little_endian" &&
           words[1] != "binary_big_endian"))
        refuse(line, "is not \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      format = words[1] == "ascii" ? Format::Ascii : Format::Binary;
    } else if (keyword == "element") {
      if (words.size() != 3 || !isCount(words[2])) refuse(line, "is not \"element NAME COUNT\"");
      // Assimp reads the count into 32 bits, wrapping past 2^32 - 1: a count that large is
      // refused rather than wrapped.
      if (words[2].size() > 10 || std::stoull(words[2]) > 0xffffffffull)
        throw GlintError("mesh " + path + ": PLY element \"" + excerpt(words[1]) + "\" declares " +
                         excerpt(words[2]) +
                         " elements, more than the 4294967295 PLY readers count");
      elements.push_back({words[1], std::stoull(words[2]), {}});
    } else if (keyword == "property") {
      const bool list =
          words.size() == 5 && words[1] == "list" && isType(words[2]) && isType(words[3]);
      if (!list && !(words.size() == 3 && isType(words[1])))
        refuse(line, "is not \"property TYPE NAME\" or \"property list TYPE TYPE NAME\"");
      if (elements.empty()) refuse(line, "names a property before any element");
      elements.back().sizeTypes.push_back(list ? words[2] : words[1]);
    }
    // Other lines are let through as Assimp reads them, as comments: real exporters write
    // them (Blender 2.47's "Created by Blender3D ..." in assimp-testmodels' Wuson.ply).
  }
  if (formats == 0) throw GlintError("mesh " + path + ": its PLY header has no format line");
  // Every element takes at least one byte (a line of its own in ASCII; an element without
  // properties is refused rather than allowed to be counted in billions from nothing).
  const uint64_t body = fileSize - std::min<uint64_t>(fileSize, bodyStart);
  // The last ASCII value may lack its final separator: one byte of slack there.
  const uint64_t limit = body + (format == Format::Ascii ? 1 : 0);
  uint64_t needed = 0;
  for (const PlyElement& e : elements) {
    // The least bytes one element takes: in ASCII a value of at least one character and a
    // separator per property, in binary each property's size.
    uint64_t minBytes = 0;
    for (const std::string& type : e.sizeTypes)
      minBytes += format == Format::Ascii ? 2 : binarySize(type);
    const uint64_t each = std::max<uint64_t>(1, minBytes);
    const uint64_t room = limit - needed;  // needed <= limit by the checks before
    if (e.count > room / each)
      throw GlintError("mesh " + path + ": its PLY header declares " + std::to_string(e.count) +
                       " \"" + excerpt(e.name) + "\" elements, each at least " +
                       std::to_string(each) + (each == 1 ? " byte" : " bytes") +
                       ", but the file has " + std::to_string(body) + " bytes after its header");
    needed += e.count * each;
  }
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
  if (lower(p.extension().string()) == ".ply")
    checkPlyCounts(path, headOf(path, kMaxPlyHeaderBytes), size);
}

}  // namespace glint
