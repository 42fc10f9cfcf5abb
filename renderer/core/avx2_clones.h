#pragma once
// GLINT_AVX2_CLONES(name, (params), (args)) { body } defines `void name(params)` built twice, for
// baseline x86-64 and for AVX2, the copy run chosen by what the CPU has. GCC, and Clang without
// LTO, make the copies with target_clones, chosen once at load. Clang 14's ThinLTO drops
// target_clones' copies at the link (LLVM issue 58740), so with LTO Clang inlines `body` into a
// baseline `name` and into a target("avx2") copy, to which `name` branches where the CPU has AVX2.
#include "core/cpu_features.h"

#ifdef GLINT_CLANG_LTO
#define GLINT_AVX2_CLONES(name, params, args)                                \
  [[gnu::always_inline]] void name##In params;                               \
  [[gnu::target("avx2")]] static void name##InAvx2 params { name##In args; } \
  void name params {                                                         \
    if (::glint::cpuFeatures().avx2) return name##InAvx2 args;               \
    name##In args;                                                           \
  }                                                                          \
  [[gnu::always_inline]] void name##In params
#else
#define GLINT_AVX2_CLONES(name, params, args) \
  [[gnu::target_clones("avx2", "default")]] void name params
#endif
