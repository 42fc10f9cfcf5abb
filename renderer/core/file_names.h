#pragma once
// What a file's name says about it.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace glint {

// The extension of `path` with its dot, in lower case (".png"); empty when it has none.
inline std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace glint
