#include "core/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>

namespace glint::interrupt {

namespace {

std::atomic<bool> gRequested{false};
std::atomic<int> gSignal{0};  // the signal that asked for the stop
std::atomic<bool> gRendering{false};
std::atomic<bool> gSampling{false};
std::atomic<unsigned> gStopSeconds{kStopSeconds};
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
  // A write or read the signal lands in goes on rather than failing with EINTR, which would
  // turn a clean stop (130) into an I/O error (1).
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

// Ends the process for signal `sig` (SIGINT or SIGTERM) from a handler. SIGINT ends it by the
// signal itself, so that a shell loop around glint stops too ($? is 130 either way); SIGTERM,
// which would read as 143, exits with 130 (CLI.md).
void endFromHandler(int sig) {
  if (gHasTemporary.load()) ::unlink(gTemporary);
  if (sig == SIGINT)
    ::kill(::getpid(), SIGINT);  // the handler is SIG_DFL by now; pending until this one returns
  else
    ::_exit(kExitCode);
}

extern "C" void onWatchdog(int) {
  // The bound's digits without snprintf, which is not async-signal-safe.
  char seconds[16];
  char* p = seconds + sizeof seconds;
  *--p = '\0';
  unsigned n = gStopSeconds.load();
  do *--p = char('0' + n % 10);
  while ((n /= 10) != 0);
  say("glint: the render did not stop within ");
  say(p);
  say(" s of the signal; stopped without writing the frame\n");
  endFromHandler(gSignal.load() == SIGINT ? SIGINT : SIGTERM);
}

extern "C" void onSignal(int sig) {
  const int savedErrno = errno;
  // The next signal ends the process at once (a write that hangs, a user who means it).
  handleWith(SIG_DFL);
  gSignal.store(sig);
  if (gRendering.load()) {
    gRequested.store(true);
    if (gSampling.load()) ::alarm(gStopSeconds.load());
    errno = savedErrno;
    return;
  }
  say(sig == SIGTERM ? "glint: terminated (SIGTERM); stopped without writing further output\n"
                     : "glint: interrupted (SIGINT); stopped without writing further output\n");
  endFromHandler(sig);
}

}  // namespace

void install() {
  handleWith(onSignal);
  struct sigaction action {};
  action.sa_handler = onWatchdog;
  sigemptyset(&action.sa_mask);
  sigaction(SIGALRM, &action, nullptr);
}

void setStopBound(unsigned seconds) { gStopSeconds.store(seconds); }

void removeTemporaryFile() {
  if (gHasTemporary.load()) ::unlink(gTemporary);
}

const std::atomic<bool>& requested() { return gRequested; }

int finish(int exitCode) {
  if (!gRequested.load()) return exitCode;
  if (gSignal.load() == SIGINT) {
    std::fflush(nullptr);
    ::signal(SIGINT, SIG_DFL);
    ::raise(SIGINT);
  }
  return kExitCode;
}

RenderPhase::RenderPhase() { gRendering.store(true); }
RenderPhase::~RenderPhase() { gRendering.store(false); }

Sampling::Sampling() {
  gSampling.store(true);
  // A signal that came before the loop began (between two frames) is seen by the loop at once,
  // and the loop is bounded all the same.
  if (gRequested.load()) ::alarm(gStopSeconds.load());
}
Sampling::~Sampling() {
  gSampling.store(false);
  ::alarm(0);
}

TemporaryFile::TemporaryFile(const std::string& path) {
  const size_t n = std::min(path.size(), sizeof gTemporary - 1);
  std::memcpy(gTemporary, path.data(), n);
  gTemporary[n] = '\0';
  gHasTemporary.store(path.size() < sizeof gTemporary);
}
TemporaryFile::~TemporaryFile() { gHasTemporary.store(false); }

}  // namespace glint::interrupt
