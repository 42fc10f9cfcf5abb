#pragma once
// Progress on stderr: a bar with percent, elapsed time and ETA on a terminal; a plain line every
// 10 % otherwise (logs, CI). Thread-safe; called once per finished tile.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

namespace glint {

// What a render will do, as far as it is known before it starts.
struct ProgressPlan {
  int64_t totalWork = 0;  // camera samples if every pixel takes every pass
  // Adaptive sampling: pixels that meet the target stop early, so totalWork is the most there
  // can be and the ETA a bound.
  bool workIsBound = false;
  // A time limit: no pass after the first runs past it (the first always finishes).
  std::optional<double> timeLimitSeconds;
  int64_t firstPassWork = 0;  // what finishes whatever the limit
};

// The share done and the time left, `elapsed` seconds into a render of `plan` that has done
// `done` of its work (seconds counted as the time limit counts them). The time left is the
// smaller of the rate's estimate for the remaining work and the time to the limit, but not less
// than the first pass needs; `fraction` is the elapsed share of elapsed + ETA, so that it
// agrees with the ETA, and is the work's share where there is no ETA yet.
struct ProgressEstimate {
  double fraction = 0;
  std::optional<double> etaSeconds;  // none until some work is done
  bool limitedByTime = false;        // the time limit, not the work, ends the render
  bool bound = false;                // adaptive: the render may end sooner
};
ProgressEstimate estimateProgress(const ProgressPlan& plan, int64_t done, double elapsed);

// "ETA 2.0s", "ETA 2.0s (time limit)", "ETA at most 9.1s", "ETA unknown".
std::string etaText(const ProgressEstimate& e);

class Progress {
 public:
  // `start`: when the render started, from which its time limit counts.
  Progress(const ProgressPlan& plan, bool enabled,
           std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());
  void advance(int64_t work, uint64_t raysSoFar);
  // Adaptive sampling, at the start of a pass: the most work there can now be, the work done
  // plus `workLeft` if the pixels the pass takes took every later pass too.
  void replan(int64_t workLeft);
  // The last line: 100 % where the render did all it was to do; where `stoppedBy` says why it
  // did not ("the time limit"), the share of the most work it did.
  void finish(const std::string& stoppedBy = "");

 private:
  void print(bool final, const std::string& stoppedBy = "");

  ProgressPlan plan_;
  int64_t done_ = 0;
  uint64_t rays_ = 0;
  bool enabled_, tty_;
  int lastDecile_ = 0;
  std::chrono::steady_clock::time_point start_, lastPrint_;
  std::mutex mutex_;
};

}  // namespace glint
