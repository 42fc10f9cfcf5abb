#pragma once
// What a file's name says about it.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace glint {

// `name` in lower case (ASCII letters only: file names are compared, not translated).
inline std::string lowerCase(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

// The extension of `path` with its dot, in lower case (".png"); empty when it has none.
inline std::string lowerExtension(const std::string& path) {
  return lowerCase(std::filesystem::path(path).extension().string());
}

}  // namespace glint
