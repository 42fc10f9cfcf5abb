#pragma once
// GLINT_AVX2_CLONES(type, name, (params), (args)) { body } defines `type name(params)` built
// twice, for baseline x86-64 and for AVX2, the copy run chosen by what the CPU has. GCC, and Clang
// without LTO, make the copies with target_clones, chosen once at load. Clang 14's ThinLTO drops
// target_clones' copies at the link (LLVM issue 58740), so with LTO Clang inlines `body` into a
// baseline `name` and into a target("avx2") copy, to which `name` branches where the CPU has AVX2.
#include "core/cpu_features.h"

#ifdef GLINT_CLANG_LTO
#define GLINT_AVX2_CLONES(type, name, params, args)                                 \
  [[gnu::always_inline]] type name##In params;                                      \
  [[gnu::target("avx2")]] static type name##InAvx2 params { return name##In args; } \
  type name params {                                                                \
    if (::glint::cpuFeatures().avx2) return name##InAvx2 args;                      \
    return name##In args;                                                           \
  }                                                                                 \
  [[gnu::always_inline]] type name##In params
#else
#define GLINT_AVX2_CLONES(type, name, params, args) \
  [[gnu::target_clones("avx2", "default")]] type name params
#endif
