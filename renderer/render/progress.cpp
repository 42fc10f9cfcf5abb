#include "render/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace glint {

ProgressEstimate estimateProgress(const ProgressPlan& plan, int64_t done, double elapsed) {
  ProgressEstimate e;
  const double total = double(std::max<int64_t>(plan.totalWork, 1));
  const double work = std::min(double(done) / total, 1.0);
  e.fraction = work;
  e.bound = plan.workIsBound;
  if (done <= 0 || !(elapsed > 0)) return e;
  const double secondsPerWork = elapsed / double(done);
  double eta = secondsPerWork * std::max(total - double(done), 0.0);
  if (plan.timeLimitSeconds) {
    const double firstPass =
        secondsPerWork * std::max(double(plan.firstPassWork) - double(done), 0.0);
    const double toLimit = std::max(*plan.timeLimitSeconds - elapsed, firstPass);
    if (toLimit < eta) {
      eta = toLimit;
      e.limitedByTime = true;
      e.bound = false;  // the limit ends it, adaptive or not
    }
  }
  e.etaSeconds = eta;
  e.fraction = elapsed / (elapsed + eta);
  return e;
}

std::string etaText(const ProgressEstimate& e) {
  if (!e.etaSeconds) return "ETA unknown";
  char text[64];
  std::snprintf(text, sizeof text, "ETA %s%.1fs%s", e.bound ? "at most " : "", *e.etaSeconds,
                e.limitedByTime ? " (time limit)" : "");
  return text;
}

Progress::Progress(const ProgressPlan& plan, bool enabled,
                   std::chrono::steady_clock::time_point start)
    : plan_(plan),
      enabled_(enabled),
      tty_(::isatty(2) != 0),
      start_(start),
      lastPrint_(std::chrono::steady_clock::now()) {}

void Progress::advance(int64_t work, uint64_t rays) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  done_ += work;
  rays_ += rays;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int decile = static_cast<int>(10 * estimateProgress(plan_, done_, elapsed).fraction);
  if (tty_ ? now - lastPrint_ > std::chrono::milliseconds(200) : decile > lastDecile_) {
    lastDecile_ = decile;
    lastPrint_ = now;
    print(false);
  }
}

void Progress::replan(int64_t workLeft) {
  std::lock_guard lock(mutex_);
  plan_.totalWork = std::min(plan_.totalWork, done_ + workLeft);
}

void Progress::finish(const std::string& stoppedBy) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  print(true, stoppedBy);
}

void Progress::print(bool final, const std::string& stoppedBy) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const ProgressEstimate e = estimateProgress(plan_, done_, elapsed);
  // The last line: 100 % and "done" for a render that did all it was to do; for one stopped
  // short, the share of time the estimate gave and what share of the most samples was taken.
  const double fraction = final && stoppedBy.empty() ? 1.0 : e.fraction;
  std::string eta = etaText(e);
  if (final && stoppedBy.empty()) eta = "done";
  if (final && !stoppedBy.empty()) {
    char taken[96];
    std::snprintf(
        taken, sizeof taken, "stopped by %s with %.3g%% of the most samples", stoppedBy.c_str(),
        100 * std::min(double(done_) / double(std::max<int64_t>(plan_.totalWork, 1)), 1.0));
    eta = taken;
  }
  const double mrays = elapsed > 0 ? static_cast<double>(rays_) / elapsed * 1e-6 : 0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = 0;
    std::fprintf(stderr, "\r[%s] %5.1f%%  %.1f Mrays/s  %.1fs elapsed  %s   ", bar, 100 * fraction,
                 mrays, elapsed, eta.c_str());
    if (final) std::fputc('\n', stderr);
  } else if (!final || lastDecile_ < 10 || !stoppedBy.empty()) {
    std::fprintf(stderr, "glint: %3.0f%%  %.1f Mrays/s  %.1fs elapsed  %s\n", 100 * fraction, mrays,
                 elapsed, eta.c_str());
  }
  std::fflush(stderr);
}

}  // namespace glint
