#pragma once
// Progress on stderr: a bar with percent, elapsed time and ETA on a terminal; a plain line every
// 10 % otherwise (logs, CI). Thread-safe; called once per finished tile.
#include <chrono>
#include <cstdint>
#include <mutex>

namespace glint {

class Progress {
 public:
  Progress(int64_t totalWork, bool enabled);
  void advance(int64_t work, uint64_t raysSoFar);
  void finish();

 private:
  void print(bool final);

  int64_t total_, done_ = 0;
  uint64_t rays_ = 0;
  bool enabled_, tty_;
  int lastDecile_ = 0;
  std::chrono::steady_clock::time_point start_, lastPrint_;
  std::mutex mutex_;
};

}  // namespace glint
