#include "core/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstring>

namespace glint::interrupt {

namespace {

std::atomic<bool> gRequested{false};
std::atomic<bool> gRendering{false};
// The temporary file to remove when the process ends from the handler: a fixed buffer, since
// the handler may only use async-signal-safe calls (unlink, write, _exit).
char gTemporary[PATH_MAX + 1] = {};
std::atomic<bool> gHasTemporary{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs lock-free flags");

void say(const char* text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void handleWith(void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

extern "C" void onSignal(int sig) {
  // The next signal ends the process at once (a write that hangs, a user who means it).
  handleWith(SIG_DFL);
  if (gRendering.load()) {
    gRequested.store(true);
    return;
  }
  if (gHasTemporary.load()) ::unlink(gTemporary);
  say(sig == SIGTERM ? "glint: terminated (SIGTERM); stopped without writing further output\n"
                     : "glint: interrupted (SIGINT); stopped without writing further output\n");
  ::_exit(kExitCode);
}

}  // namespace

void install() { handleWith(onSignal); }

const std::atomic<bool>& requested() { return gRequested; }

RenderPhase::RenderPhase() { gRendering.store(true); }
RenderPhase::~RenderPhase() { gRendering.store(false); }

TemporaryFile::TemporaryFile(const std::string& path) {
  const size_t n = std::min(path.size(), sizeof gTemporary - 1);
  std::memcpy(gTemporary, path.data(), n);
  gTemporary[n] = '\0';
  gHasTemporary.store(path.size() < sizeof gTemporary);
}
TemporaryFile::~TemporaryFile() { gHasTemporary.store(false); }

}  // namespace glint::interrupt
