#pragma once
// A PLY file's header, parsed once for both the check before reading (io/mesh_limits.h) and the
// reader (io/ply_reader.h). Only PLY 1.0's lines are accepted: Assimp 5.2's reader never
// returned from a header that repeated and garbled them, and Glint's reader trusts no more.
#include <cstdint>
#include <string>
#include <vector>

namespace glint {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

// The scalar types of PLY 1.0, under either of their names (char or int8, float or float32).
enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // a list's item type
  bool list = false;
  PlyType countType = PlyType::UInt8;  // a list's count type
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;  // at most 2^32 - 1
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  std::vector<PlyElement> elements;
  uint64_t bodyStart = 0;  // the first byte after the end_header line
  uint64_t bodyLine = 0;   // its line number, lines ended as the header's are (a lone CR too)
};

// A PLY header longer than this (comments, mostly) is refused rather than read on.
inline constexpr size_t kMaxPlyHeaderBytes = size_t{1} << 20;

// Bytes of one binary value.
int plyTypeSize(PlyType type);

// Parses the header at the start of `head` (the file's first bytes, up to kMaxPlyHeaderBytes;
// `fileSize` the whole file's). Throws GlintError naming `path` when a line is not PLY 1.0's,
// the format line is missing or repeated, or no end_header line ends it.
PlyHeader parsePlyHeader(const std::string& path, const std::string& head, uint64_t fileSize);

// Throws GlintError naming `path` when an element's count times the least bytes one element can
// take (a value and a separator per property in ASCII, each property's size in binary; an
// empty list is its count alone) exceeds the bytes after the header. After this, vectors sized
// by the counts are at most a few times the file's size.
void checkPlyElementsFitInTheFile(const std::string& path, const PlyHeader& header,
                                  uint64_t fileSize);

}  // namespace glint
