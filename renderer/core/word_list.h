#pragma once
// A list in a message as it is read aloud: "a", "a and b", "a, b and c".
#include <string>
#include <vector>

namespace glint {

inline std::string wordList(const std::vector<std::string>& items) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return text;
}

}  // namespace glint
