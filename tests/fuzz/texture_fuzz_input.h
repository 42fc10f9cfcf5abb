#pragma once
// The texture fuzzer's input and oracle (tests/fuzz/texture_fuzzer.cpp), shared with the
// regression test that replays tests/fuzz/regressions-texture/ in every build: the first byte
// picks the format (0 PNG, 1 JPEG, 2 Radiance HDR), the rest are the file's bytes, opened as a
// texture embedded in a glTF is (openImageTextureInMemory). The only acceptable outcomes are a
// texture, or a GlintError naming the file.
#include <exception>
#include <iterator>
#include <string>

#include "core/error.h"
#include "io/own_texture_readers.h"
#include "io/texture_file.h"

namespace glint::fuzz {

// What is wrong with how `input` was read: empty if nothing. `*skipped`: the input is no
// texture input (no format byte), or its reader leaves it to OpenImageIO, whose module is not
// what the fuzzer tests.
inline std::string textureReadProblem(const std::string& input, bool* skipped) {
  *skipped = input.empty() || static_cast<unsigned char>(input[0]) >= std::size(kOwnTextureReaders);
  if (*skipped) return "";
  const OwnTextureReader& format = *kOwnTextureReaders[static_cast<unsigned char>(input[0])];
  const std::string bytes = input.substr(1);
  GlintOiioTextureInfo info{};
  char error[512] = "";
  bool declined = false;
  void* handle = format.openMemory(format.name, bytes.data(), bytes.size(), &info, error,
                                   sizeof error, &declined);
  if (handle) format.functions().close(handle);
  *skipped = declined;
  if (declined) return "";
  try {
    openImageTextureInMemory(format.name, bytes);
  } catch (const GlintError& e) {
    if (std::string(e.what()).find(format.name) == std::string::npos)
      return std::string("an error not naming the file: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("an exception other than GlintError: ") + e.what();
  }
  return "";
}

}  // namespace glint::fuzz
