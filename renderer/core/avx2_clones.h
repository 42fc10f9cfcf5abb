#pragma once
// GLINT_AVX2_CLONES(type, name, (params), (args)) { body } defines `type name(params)` built
// twice, for baseline x86-64 and for AVX2, the copy run chosen by what the CPU has. GCC, and Clang
// without LTO, make the copies with target_clones, chosen once at load. Clang 14's LTO drops what
// target_clones' copies call, and the link fails (LLVM issue 58740), so with LTO Clang inlines
// `body` into a baseline `name` and into a target("avx2") copy, to which `name` branches where the
// CPU has AVX2. For functions at namespace scope, with no default arguments and no comma in `type`;
// `name##In` keeps external linkage, as a class may befriend `name` (mip_pyramid.h).
#include "core/cpu_features.h"

#ifdef GLINT_CLANG_LTO
#ifndef __clang__
#error "GLINT_CLANG_LTO is for Clang's LTO builds only (CMakeLists.txt sets it)"
#endif
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
