#pragma once
// Runs a function in a forked child, for tests of what ends a process (limits, signals,
// std::terminate) without ending the test.
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <utility>

namespace glint::test {

// Runs `child` (returning an exit code) in a forked process with stderr captured; returns its
// exit status (or 128 + the signal that ended it) and what it wrote to stderr.
template <class Child>
std::pair<int, std::string> inChild(Child child) {
  int pipeFds[2];
  if (::pipe(pipeFds) != 0) return {-1, "pipe failed"};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipeFds[0]);
    ::dup2(pipeFds[1], STDERR_FILENO);
    ::_exit(child());
  }
  ::close(pipeFds[1]);
  std::string text;
  char buf[512];
  for (ssize_t n; (n = ::read(pipeFds[0], buf, sizeof buf)) > 0;) text.append(buf, size_t(n));
  ::close(pipeFds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), text};
}

}  // namespace glint::test
