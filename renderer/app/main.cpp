#include "app/commands.h"

#include <csignal>

int main(int argc, char** argv) {
  // A file size limit should fail the write (EFBIG) so the temporary file is cleaned up, not
  // kill the process half-way through it.
  std::signal(SIGXFSZ, SIG_IGN);
  return glint::runCli(argc, argv);
}
