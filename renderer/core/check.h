#pragma once
// CHECK guards internal invariants (never user input): a failure is a Glint bug, reported with
// its location, and aborts.
#include <cstdio>
#include <cstdlib>

#define GLINT_CHECK(cond)                                                                     \
  do {                                                                                        \
    if (!(cond)) {                                                                            \
      std::fprintf(stderr, "glint: internal check failed at %s:%d: %s\n", __FILE__, __LINE__, \
                   #cond);                                                                    \
      std::abort();                                                                           \
    }                                                                                         \
  } while (0)
