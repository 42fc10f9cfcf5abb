// Seconds on the steady clock since a start: the build, load and bench times Glint reports.
#pragma once

#include <chrono>

namespace glint {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace glint
