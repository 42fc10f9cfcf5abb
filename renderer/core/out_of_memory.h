#pragma once
// Running out of memory, in any library, ends Glint with exit 1 and "out of memory while
// reading X" (CLI.md), never with std::terminate or a signal:
// - whileDoing() names what a piece of work is ("reading mesh big.obj") and turns the
//   std::bad_alloc it throws, or a thread it could not start, into OutOfMemoryError;
// - install() makes the failures that no catch can reach end the same way: a bad_alloc thrown
//   through a noexcept function (nlohmann-json's destructor allocates), from a library's own
//   thread, or out of a destructor while unwinding ends in std::terminate, whose handler then
//   reports it with the activity under way (as it reports an OutOfMemoryError being handled
//   when a library calls std::terminate itself); and a reserve of address space is given back at
//   the first failed `new`, so that unwinding has memory to work with.
#include <new>
#include <string>
#include <system_error>
#include <utility>

#include "core/error.h"

namespace glint::out_of_memory {

// Installs the terminate handler and the reserve; main() calls it first.
void install();

// While one exists, this thread's work is `activity` ("reading scene big.json"), for
// messages. Scopes nest; the innermost names the work.
class Activity {
 public:
  explicit Activity(std::string activity);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

 private:
  std::string previous_;
};

// "out of memory while reading scene big.json" for the innermost Activity, or "out of memory".
std::string message();

// Whether `e` says a thread or a mapping could not be made for want of memory or address
// space: a std::system_error of EAGAIN (pthread_create under RLIMIT_AS) or ENOMEM, or another
// exception whose message ends in their strerror text (TBB's "pthread_create has failed:
// Resource temporarily unavailable").
bool isResourceShortage(const std::exception& e);

// Runs `work` as `activity`; std::bad_alloc and resource shortages become OutOfMemoryError.
template <class Work>
decltype(auto) whileDoing(const std::string& activity, Work&& work) {
  const Activity scope(activity);
  try {
    return std::forward<Work>(work)();
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory while " + activity);
  } catch (const GlintError&) {
    throw;  // OutOfMemoryError among them: named already
  } catch (const std::exception& e) {
    if (!isResourceShortage(e)) throw;
    throw OutOfMemoryError("out of memory while " + activity + " (" + e.what() + ")");
  }
}

}  // namespace glint::out_of_memory
