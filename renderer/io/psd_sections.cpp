#include "io/psd_sections.h"

#include <array>
#include <string_view>

namespace glint {

namespace {

// A big-endian unsigned integer of `bytes` (at most 8) bytes at `offset`; false past the end.
bool readBigEndian(const ReadAt& read, uint64_t offset, int bytes, uint64_t& value) {
  std::array<char, 8> b{};
  if (!read(offset, b.data(), size_t(bytes))) return false;
  value = 0;
  for (int i = 0; i < bytes; ++i) value = value << 8 | static_cast<unsigned char>(b[size_t(i)]);
  return true;
}

}  // namespace

std::string psdSectionsPastTheEnd(const ReadAt& read, uint64_t size) {
  // The header (Adobe's file format specification): "8BPS", version 1 (PSD) or 2 (PSB), six
  // reserved bytes, channels, height, width, depth and colour mode: 26 bytes.
  constexpr uint64_t kHeaderBytes = 26;
  std::array<char, 4> signature{};
  uint64_t version = 0;
  if (size < kHeaderBytes || !read(0, signature.data(), 4) ||
      std::string_view(signature.data(), 4) != "8BPS" || !readBigEndian(read, 4, 2, version) ||
      (version != 1 && version != 2))
    return "";
  struct Section {
    const char* name;
    int lengthBytes;
  };
  // The layer and mask section's length takes 8 bytes in a PSB file.
  const Section sections[] = {{"colour mode data", 4},
                              {"image resources", 4},
                              {"layer and mask information", version == 2 ? 8 : 4}};
  uint64_t at = kHeaderBytes;
  for (const Section& s : sections) {
    uint64_t length = 0;
    if (size - at < uint64_t(s.lengthBytes) || !readBigEndian(read, at, s.lengthBytes, length))
      return std::string("it ends before its ") + s.name + " (a cut or damaged Photoshop file)";
    at += uint64_t(s.lengthBytes);
    if (length > size - at)
      return "its " + std::string(s.name) + " claims " + std::to_string(length) + " bytes, but " +
             std::to_string(size - at) + " remain (a cut or damaged Photoshop file)";
    at += length;
  }
  return "";
}

}  // namespace glint
