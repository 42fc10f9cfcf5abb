#pragma once
// Shared by the tests of Glint's own texture readers (io/own_texture_readers.h): a
// file or its bytes read by one of them and by OpenImageIO's module, which read them before, and
// the two readings compared: the same header, oiio:ColorSpace and floats bit for bit, or both
// refusing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/file_names.h"
#include "film/oiio_module.h"
#include "io/own_texture_readers.h"
#include "io/texture_bands.h"
#include "io/texture_file.h"
#include "io/texture_formats.h"
#include "test_util.h"

namespace glint::test {

using Bytes = std::vector<unsigned char>;

// What one reader made of a file: refused (with its message), or its header and texels.
struct Reading {
  bool declined = false, ok = false;
  std::string error;
  GlintOiioTextureInfo info{};
  std::vector<float> texels;
};

// Rows per band of OpenImageIO's module (the reference) and of Glint's reader (under test):
// boundaries that differ, and small ones that cross many of them (io/texture_file.cpp reads
// bands).
inline constexpr int kOpenImageIOBand = 5;
inline constexpr int kOwnBand = 3;

inline void readRows(Reading& r, void* handle, const oiio_module::TextureFunctions& functions,
                     int bandRows) {
  const std::unique_ptr<void, GlintOiioTextureClose> opened(handle, functions.close);
  r.ok = readInBands(functions, handle, r.info.width, r.info.height, r.info.channels, bandRows,
                     r.texels, r.error);
}

inline Reading readWith(const OwnTextureReader& reader, const std::string& path) {
  Reading r;
  char error[512] = "";
  void* handle = reader.open(path, &r.info, error, sizeof error, &r.declined);
  r.error = error;
  if (handle) readRows(r, handle, reader.functions(), kOwnBand);
  return r;
}

inline Reading readBytesWith(const OwnTextureReader& reader, const std::string& name,
                             const Bytes& bytes) {
  Reading r;
  char error[512] = "";
  void* handle = reader.openMemory(name, bytes.data(), bytes.size(), &r.info, error, sizeof error,
                                   &r.declined);
  r.error = error;
  if (handle) readRows(r, handle, reader.functions(), kOwnBand);
  return r;
}

inline Reading readWithOpenImageIO(const std::string& path) {
  Reading r;
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(path);
  char error[512] = "";
  void* handle =
      functions.open(path.c_str(), textureReaderFormat(path).c_str(), &r.info, error, sizeof error);
  r.error = error;
  if (handle) readRows(r, handle, functions, kOpenImageIOBand);
  return r;
}

inline Reading readBytesWithOpenImageIO(const std::string& name, const Bytes& bytes) {
  Reading r;
  const oiio_module::TextureFunctions& functions = oiio_module::textureFunctions(name);
  char error[512] = "";
  void* handle = functions.openMemory(name.c_str(), textureReaderFormat(name).c_str(), bytes.data(),
                                      bytes.size(), &r.info, error, sizeof error);
  r.error = error;
  if (handle) readRows(r, handle, functions, kOpenImageIOBand);
  return r;
}

// Both readers accept it with the same header, colour space and floats, bit for bit, or both
// refuse it.
inline void expectSameReading(const char* library, const Reading& ours, const Reading& theirs,
                              const std::string& what) {
  ASSERT_FALSE(ours.declined) << what;
  ASSERT_EQ(ours.ok, theirs.ok) << what << ": " << library << ": " << ours.error
                                << "; OpenImageIO: " << theirs.error;
  if (!ours.ok) {
    EXPECT_FALSE(ours.error.empty()) << what;
    return;
  }
  EXPECT_EQ(ours.info.width, theirs.info.width) << what;
  EXPECT_EQ(ours.info.height, theirs.info.height) << what;
  EXPECT_EQ(ours.info.channels, theirs.info.channels) << what;
  EXPECT_EQ(ours.info.isFloat, theirs.info.isFloat) << what;
  EXPECT_EQ(ours.info.bytesPerChannel, theirs.info.bytesPerChannel) << what;
  EXPECT_EQ(ours.info.tileHeight, theirs.info.tileHeight) << what;
  EXPECT_STREQ(ours.info.colorspace, theirs.info.colorspace) << what;
  ASSERT_EQ(ours.texels.size(), theirs.texels.size()) << what;
  EXPECT_EQ(std::memcmp(ours.texels.data(), theirs.texels.data(), ours.texels.size() * 4), 0)
      << what;
}

inline void compareFile(const OwnTextureReader& reader, const std::string& path) {
  expectSameReading(reader.library, readWith(reader, path), readWithOpenImageIO(path), path);
}

inline void compareBytes(const OwnTextureReader& reader, const std::string& name,
                         const Bytes& bytes) {
  expectSameReading(reader.library, readBytesWith(reader, name, bytes),
                    readBytesWithOpenImageIO(name, bytes), name);
}

// compareBytes for the `call`th of many damaged files, one that Glint's reader leaves to
// OpenImageIO (declined) left out. Under AddressSanitizer, where each of OpenImageIO's reads takes
// about 0.1 s, only every eighth is compared and the others are read by Glint's reader alone:
// there the test looks for memory faults in Glint's reader, which every file still reaches; the
// comparison of them all is the Release suite's.
inline void compareDamaged(const OwnTextureReader& reader, const std::string& name,
                           const Bytes& bytes, size_t call) {
  const Reading ours = readBytesWith(reader, name, bytes);
  if (ours.declined) return;
  if (!kAddressSanitizer || call % 8 == 0)
    return expectSameReading(reader.library, ours, readBytesWithOpenImageIO(name, bytes), name);
  if (!ours.ok) {
    EXPECT_FALSE(ours.error.empty()) << name;
  }
}

inline void append(Bytes& to, const Bytes& from) { to.insert(to.end(), from.begin(), from.end()); }

// The texture reader refuses `path` with a message naming it and holding `reason`.
inline void expectRefusedNaming(const std::string& path, const std::string& reason) {
  try {
    openImageTexture(path);
    ADD_FAILURE() << path << " was read";
  } catch (const GlintError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << what;
  }
}

inline void writeBytes(const std::string& path, const Bytes& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Every file under `root` whose extension (in any case) is one of `extensions`, build folders
// and .git left out, sorted.
inline std::vector<std::string> filesUnder(const std::filesystem::path& root,
                                           const std::vector<std::string>& extensions) {
  namespace fs = std::filesystem;
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind("build", 0) == 0 || name == ".git")) {
      it.disable_recursion_pending();
      continue;
    }
    const std::string extension = lowerCase(it->path().extension().string());
    if (it->is_regular_file() &&
        std::find(extensions.begin(), extensions.end(), extension) != extensions.end())
      found.push_back(it->path().string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace glint::test
