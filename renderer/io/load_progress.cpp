#include "io/load_progress.h"

#include <algorithm>
#include <cstdio>

#include "core/log.h"
#include "core/seconds_since.h"

namespace glint {

LoadProgress::LoadProgress(std::string what, const std::string& about, uint64_t totalWork, bool big)
    : what_(std::move(what)),
      total_(totalWork > 0 ? totalWork : 1),
      nextLine_(total_ / 4),
      big_(big),
      start_(std::chrono::steady_clock::now()) {
  if (big_) log::info("reading " + what_ + ": " + about);
}

void LoadProgress::print(uint64_t done) {
  quarter_ = static_cast<int>(std::min<uint64_t>(4 * done / total_, 3));
  nextLine_ = total_ / 4 * uint64_t(quarter_ + 1);
  if (quarter_ >= 3) nextLine_ = UINT64_MAX;  // the end is finish()'s line
  char line[64];
  std::snprintf(line, sizeof line, ": %d%%, %.1f s", 25 * quarter_, secondsSince(start_));
  log::info("reading " + what_ + line);
}

void LoadProgress::finish(const std::string& result) {
  if (!big_) return;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, " in %.2f s", secondsSince(start_));
  log::info("read " + what_ + ": " + result + seconds);
}

}  // namespace glint
