#include "app/commands.h"
#include "core/interrupt.h"
#include "core/out_of_memory.h"

#include <csignal>

int main(int argc, char** argv) {
  // A file size limit should fail the write (EFBIG) so the temporary file is cleaned up, not
  // kill the process half-way through it.
  std::signal(SIGXFSZ, SIG_IGN);
  // A reader that goes away (`glint render ... 2>&1 | head -1`) should cost the progress lines
  // it no longer reads (their writes fail with EPIPE), not the frame.
  std::signal(SIGPIPE, SIG_IGN);
  glint::interrupt::install();      // before anything is loaded: every phase can be interrupted
  glint::out_of_memory::install();  // likewise: running out of memory is exit 1 in every phase
  return glint::interrupt::finish(glint::runCli(argc, argv));
}
