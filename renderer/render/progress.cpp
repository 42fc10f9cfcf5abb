#include "render/progress.h"

#include <unistd.h>

#include <cstdio>

namespace glint {

Progress::Progress(int64_t totalWork, bool enabled)
    : total_(totalWork > 0 ? totalWork : 1),
      enabled_(enabled),
      tty_(::isatty(2) != 0),
      start_(std::chrono::steady_clock::now()),
      lastPrint_(start_) {}

void Progress::advance(int64_t work, uint64_t rays) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  done_ += work;
  rays_ += rays;
  const auto now = std::chrono::steady_clock::now();
  const int decile = static_cast<int>(10 * done_ / total_);
  if (tty_ ? now - lastPrint_ > std::chrono::milliseconds(200) : decile > lastDecile_) {
    lastDecile_ = decile;
    lastPrint_ = now;
    print(false);
  }
}

void Progress::finish() {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  print(true);
}

void Progress::print(bool final) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = static_cast<double>(done_) / static_cast<double>(total_);
  char eta[32] = "ETA unknown";  // until some work is done
  if (fraction > 0)
    std::snprintf(eta, sizeof eta, "ETA %.1fs", elapsed * (1 - fraction) / fraction);
  const double mrays = elapsed > 0 ? static_cast<double>(rays_) / elapsed * 1e-6 : 0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = 0;
    std::fprintf(stderr, "\r[%s] %5.1f%%  %.1f Mrays/s  %.1fs elapsed  %s   ", bar, 100 * fraction,
                 mrays, elapsed, eta);
    if (final) std::fputc('\n', stderr);
  } else if (!final || fraction < 1) {
    std::fprintf(stderr, "glint: %3.0f%%  %.1f Mrays/s  %.1fs elapsed  %s\n", 100 * fraction, mrays,
                 elapsed, eta);
  }
  std::fflush(stderr);
}

}  // namespace glint
