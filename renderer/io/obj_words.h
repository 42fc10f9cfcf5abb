#pragma once
// Words of an OBJ or MTL line, split without a stream or a string a word: Glint's checks read
// every line of OBJ files of up to 1 GiB before Assimp does (io/mesh_limits.cpp,
// io/obj_smoothing.cpp).
#include <algorithm>
#include <string_view>

namespace glint {

// The next word of `line`, split at `spaces`, taken off it; empty at the line's end.
inline std::string_view takeObjWord(std::string_view& line, const char* spaces = " \t\r\v\f") {
  const size_t begin = std::min(line.find_first_not_of(spaces), line.size());
  const size_t end = std::min(line.find_first_of(spaces, begin), line.size());
  const std::string_view word = line.substr(begin, end - begin);
  line.remove_prefix(end);
  return word;
}

}  // namespace glint
