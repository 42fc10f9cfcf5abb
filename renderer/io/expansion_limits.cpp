#include "io/expansion_limits.h"

namespace glint {

std::string countText(uint64_t count) {
  constexpr uint64_t kSaturated = std::numeric_limits<uint64_t>::max();
  return count == kSaturated ? "more than " + std::to_string(kSaturated - 1)
                             : std::to_string(count);
}

std::string pathText(const std::vector<std::string>& names, size_t keep) {
  std::string out;
  const size_t head = keep / 2, tail = keep - head;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names.size() > keep && i == head) {
      out += " > … (" + std::to_string(names.size() - keep) + " more)";
      i = names.size() - tail - 1;
      continue;
    }
    out += (out.empty() ? "" : " > ") + names[i];
  }
  return out;
}

}  // namespace glint
