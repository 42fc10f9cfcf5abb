#pragma once
// Progress of loading a big input (a mesh of a million faces or 50 MB), as info lines on
// stderr through core/log.h, so --quiet silences them: a line when it starts, one at each
// quarter of the work and one when it ends, with the time taken. A load of a few seconds
// gets a handful of lines, on a terminal or in a log alike; small inputs get none.
#include <chrono>
#include <cstdint>
#include <string>

namespace glint {

class LoadProgress {
 public:
  // `what` names the input ("mesh scan.ply"); `about` says what it holds, for the first line.
  // Prints nothing unless `big`.
  LoadProgress(std::string what, const std::string& about, uint64_t totalWork, bool big);
  // `done` of the total work is finished; cheap when no line is due.
  void update(uint64_t done) {
    if (big_ && done >= nextLine_) print(done);
  }
  // The last line: `result` says what was loaded.
  void finish(const std::string& result);

 private:
  void print(uint64_t done);

  std::string what_;
  uint64_t total_, nextLine_;
  int quarter_ = 0;
  bool big_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace glint
