#include "io/ply_header.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>

#include "core/error.h"

namespace glint {

namespace {

std::optional<PlyType> typeNamed(const std::string& name) {
  static const std::pair<const char*, PlyType> kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [n, type] : kTypes)
    if (name == n) return type;
  return std::nullopt;
}

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

int plyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

PlyHeader parsePlyHeader(const std::string& path, const std::string& head, uint64_t fileSize) {
  size_t bodyStart = 0;
  const std::vector<std::string> lines = headerLines(head, &bodyStart);
  // Assimp 5.2's PLY reader looped forever on a header that never ends (even a four-line file).
  if (bodyStart == std::string::npos)
    throw GlintError("mesh " + path + ": its PLY header has no end_header line" +
                     (head.size() < fileSize
                          ? " in its first " + std::to_string(kMaxPlyHeaderBytes) + " bytes"
                          : std::string()));
  PlyHeader header;
  header.bodyStart = bodyStart;
  header.bodyLine = lines.size() + 1;
  // The header's lines must be PLY 1.0's as its specification writes them (one "ply", one
  // format line, elements with a count, properties of known types): Assimp 5.2's reader never
  // returned from a binary file whose header repeated and garbled them (a 190-byte file, found
  // by glint_fuzz_mesh), so anything else is refused.
  const auto refuse = [&](const std::string& line, const char* why) {
    throw GlintError("mesh " + path + ": its PLY header line \"" + excerpt(line) + "\" " + why);
  };
  const auto isCount = [](const std::string& t) {
    return !t.empty() && t.size() <= 20 &&
           std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c); });
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
      header.format = words[1] == "ascii"                  ? PlyFormat::Ascii
                      : words[1] == "binary_little_endian" ? PlyFormat::BinaryLittleEndian
                                                           : PlyFormat::BinaryBigEndian;
    } else if (keyword == "element") {
      if (words.size() != 3 || !isCount(words[2])) refuse(line, "is not \"element NAME COUNT\"");
      // Counts are read into 32 bits by PLY readers (Assimp's wrapped past 2^32 - 1), and
      // Glint's indices are 32-bit: a count that large is refused rather than wrapped.
      if (words[2].size() > 10 || std::stoull(words[2]) > 0xffffffffull)
        throw GlintError("mesh " + path + ": PLY element \"" + excerpt(words[1]) + "\" declares " +
                         excerpt(words[2]) +
                         " elements, more than the 4294967295 PLY readers count");
      header.elements.push_back({words[1], std::stoull(words[2]), {}});
    } else if (keyword == "property") {
      const bool list =
          words.size() == 5 && words[1] == "list" && typeNamed(words[2]) && typeNamed(words[3]);
      if (!list && !(words.size() == 3 && typeNamed(words[1])))
        refuse(line, "is not \"property TYPE NAME\" or \"property list TYPE TYPE NAME\"");
      if (header.elements.empty()) refuse(line, "names a property before any element");
      PlyProperty p;
      p.list = list;
      p.name = words.back();
      p.type = *typeNamed(list ? words[3] : words[1]);
      if (list) p.countType = *typeNamed(words[2]);
      header.elements.back().properties.push_back(p);
    }
    // Other lines are read past as comments: real exporters write them (Blender 2.47's
    // "Created by Blender3D ..." in assimp-testmodels' Wuson.ply), and Assimp reads them so.
  }
  if (formats == 0) throw GlintError("mesh " + path + ": its PLY header has no format line");
  return header;
}

void checkPlyElementsFitInTheFile(const std::string& path, const PlyHeader& header,
                                  uint64_t fileSize) {
  const bool ascii = header.format == PlyFormat::Ascii;
  // Every element takes at least one byte (a line of its own in ASCII; an element without
  // properties is refused rather than allowed to be counted in billions from nothing).
  const uint64_t body = fileSize - std::min<uint64_t>(fileSize, header.bodyStart);
  // The last ASCII value may lack its final separator: one byte of slack there.
  const uint64_t limit = body + (ascii ? 1 : 0);
  uint64_t needed = 0;
  for (const PlyElement& e : header.elements) {
    // The least bytes one element takes: in ASCII a value of at least one character and a
    // separator per property, in binary each property's size (a list's count's).
    uint64_t minBytes = 0;
    for (const PlyProperty& p : e.properties)
      minBytes += ascii ? 2 : uint64_t(plyTypeSize(p.list ? p.countType : p.type));
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

}  // namespace glint
