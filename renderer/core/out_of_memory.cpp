#include "core/out_of_memory.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <string_view>

#include "core/interrupt.h"

namespace glint::out_of_memory {

namespace {

// The innermost activity, in a fixed buffer: the terminate handler reads it without allocating.
std::mutex gMutex;
char gActivity[512] = {};

// Address space handed back at the first failed `new`: unwinding from it allocates (messages,
// nlohmann-json's destructor), and with nothing left it would throw again where it cannot.
constexpr size_t kReserveBytes = size_t{32} << 20;
void* gReserve = nullptr;
std::terminate_handler gPreviousTerminate = nullptr;

void say(const char* text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void onNewFailure() {
  void* reserve = std::exchange(gReserve, nullptr);
  if (!reserve) {
    std::set_new_handler(nullptr);
    throw std::bad_alloc();
  }
  std::free(reserve);
  // Fail this allocation all the same: the reserve is for the unwinding that follows, not for
  // one more step of the work that ran out.
  throw std::bad_alloc();
}

[[noreturn]] void onTerminate() {
  bool outOfMemory = false;
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      outOfMemory = true;
    } catch (const OutOfMemoryError& x) {
      // Being handled when a library gave up: Embree, releasing a scene it could not build for
      // want of memory, calls std::terminate itself.
      interrupt::removeTemporaryFile();
      say("glint: error: ");
      say(x.what());
      say("\n");
      ::_exit(1);
    } catch (const std::exception& x) {
      outOfMemory = isResourceShortage(x);
    } catch (...) {
    }
  }
  if (!outOfMemory) {
    if (gPreviousTerminate) gPreviousTerminate();
    std::abort();
  }
  interrupt::removeTemporaryFile();
  say("glint: error: out of memory");
  if (gActivity[0] != '\0') {
    say(" while ");
    say(gActivity);
  }
  say("\n");
  ::_exit(1);  // the other threads may hold locks; nothing more can be done safely
}

void setActivity(const std::string& activity) {
  const size_t n = std::min(activity.size(), sizeof gActivity - 1);
  std::memcpy(gActivity, activity.data(), n);
  gActivity[n] = '\0';
}

}  // namespace

void install() {
  gReserve = std::malloc(kReserveBytes);
  std::set_new_handler(onNewFailure);
  gPreviousTerminate = std::set_terminate(onTerminate);
}

Activity::Activity(std::string activity) {
  const std::lock_guard<std::mutex> lock(gMutex);
  previous_ = gActivity;
  setActivity(activity);
}

Activity::~Activity() {
  const std::lock_guard<std::mutex> lock(gMutex);
  setActivity(previous_);
}

std::string message() {
  const std::lock_guard<std::mutex> lock(gMutex);
  return gActivity[0] == '\0' ? "out of memory" : "out of memory while " + std::string(gActivity);
}

bool isResourceShortage(const std::exception& e) {
  if (const auto* s = dynamic_cast<const std::system_error*>(&e)) {
    const std::error_code& c = s->code();
    if (c.category() == std::generic_category() || c.category() == std::system_category())
      return c.value() == EAGAIN || c.value() == ENOMEM;
  }
  const std::string_view what = e.what();
  for (const int code : {EAGAIN, ENOMEM}) {
    const std::string_view text = std::strerror(code);
    if (what.size() >= text.size() && what.substr(what.size() - text.size()) == text) return true;
  }
  return false;
}

}  // namespace glint::out_of_memory
