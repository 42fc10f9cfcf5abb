// The bound on stopping a render after SIGINT or SIGTERM (core/interrupt.h): a render thread
// that never polls the flag (one waiting inside a library) cannot keep the process alive.
#include "core/interrupt.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include "core/child_process.h"

namespace glint {
namespace {

TEST(Interrupt, ARenderThatNeverStopsEndsWithinTheBoundWithExit130) {
  // The signal comes while sampling; nothing ever looks at the flag (pause() stands for a
  // thread stuck in OpenImageIO). With a 1 s bound the watchdog ends the process: 130, and it
  // says why.
  const auto [status, text] = test::inChild([] {
    interrupt::install();
    interrupt::setStopBound(1);
    const interrupt::RenderPhase rendering;
    const interrupt::Sampling sampling;
    ::kill(::getpid(), SIGTERM);
    for (;;) ::pause();
    return 0;
  });
  EXPECT_EQ(status, 130) << text;
  EXPECT_EQ(text,
            "glint: the render did not stop within 1 s of the signal; stopped without "
            "writing the frame\n");
}

TEST(Interrupt, ARenderThatStopsInTimeDisarmsTheWatchdog) {
  // The loop sees the flag and returns (Sampling ends) before the bound: the process goes on to
  // write its partial frame, for as long as that takes (here 2 s, twice the bound), and exits
  // as it chooses.
  const auto [status, text] = test::inChild([] {
    interrupt::install();
    interrupt::setStopBound(1);
    const interrupt::RenderPhase rendering;
    {
      const interrupt::Sampling sampling;
      ::kill(::getpid(), SIGTERM);
      if (!interrupt::requested()) return 2;
    }
    ::sleep(2);
    return 0;
  });
  EXPECT_EQ(status, 0) << text;
  EXPECT_EQ(text, "");
}

}  // namespace
}  // namespace glint
