#include "film/exr_input.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace glint {

void checkExrHeaders(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t fileSize = std::filesystem::file_size(path, ec);
  if (!in || ec) throw UsageError("cannot read " + path);
  const auto fail = [&](const std::string& why) {
    throw UsageError("cannot read " + path + ": " + why);
  };
  unsigned char start[8] = {};
  if (!in.read(reinterpret_cast<char*>(start), 8) || start[0] != 0x76 || start[1] != 0x2f ||
      start[2] != 0x31 || start[3] != 0x01)
    fail("not an OpenEXR file");
  const bool multipart = (start[5] & 0x10) != 0;  // version flags, byte 1 of the flags
  // A null-terminated name of at most 255 characters (long names), "" at the end of a header.
  const auto readName = [&]() {
    std::string name;
    for (char c; in.get(c);) {
      if (c == '\0') return name;
      if (name.size() == 255) fail("a header name is longer than 255 characters");
      name.push_back(c);
    }
    fail("the header is cut short");
    return name;
  };
  for (int part = 0;; ++part) {
    std::string name = readName();
    if (name.empty()) {
      // The end of the headers: after one for a single-part file, after an empty one (read as
      // an empty first name) for a multi-part file.
      if (!multipart || part > 0) return;
      fail("a multi-part file without parts");
    }
    while (!name.empty()) {
      const std::string type = readName();
      int32_t size = 0;
      if (!in.read(reinterpret_cast<char*>(&size), 4)) fail("the header is cut short");
      const uint64_t at = uint64_t(in.tellg());
      if (size < 0 || uint64_t(size) > fileSize - std::min(at, fileSize))
        fail("its header attribute \"" + excerpt(name) + "\" declares " + std::to_string(size) +
             " bytes, but the file has " + std::to_string(fileSize - std::min(at, fileSize)) +
             " left");
      in.seekg(size, std::ios::cur);
      name = readName();
    }
    if (!multipart) return;
  }
}

std::unique_ptr<OIIO::ImageInput> openExr(const std::string& path) {
  checkExrHeaders(path);
  auto in = OIIO::ImageInput::create("openexr");
  if (!in) throw GlintError("OpenImageIO has no OpenEXR reader: " + OIIO::geterror());
  OIIO::ImageSpec spec;
  if (!in->open(path, spec))
    throw UsageError("cannot read " + path + ": " + excerpt(in->geterror()));
  return in;
}

}  // namespace glint
