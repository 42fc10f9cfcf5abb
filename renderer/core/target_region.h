#pragma once
// GLINT_TARGET_REGION_BEGIN("avx2") … GLINT_TARGET_REGION_END: every function declared between
// them is built for that instruction set, as if each carried [[gnu::target("avx2")]], and the
// rest of the file for baseline x86-64. A flag for the whole file would build its copies of
// inline library functions for the instruction set too, which the linker may then pick for
// every caller: a file includes every header it needs but its region's own before the region.
#define GLINT_PRAGMA(...) _Pragma(#__VA_ARGS__)
#ifdef __clang__
#define GLINT_TARGET_REGION_BEGIN(isa) \
  GLINT_PRAGMA(clang attribute push(__attribute__((target(isa))), apply_to = function))
#define GLINT_TARGET_REGION_END GLINT_PRAGMA(clang attribute pop)
#else
#define GLINT_TARGET_REGION_BEGIN(isa) GLINT_PRAGMA(GCC push_options) GLINT_PRAGMA(GCC target(isa))
#define GLINT_TARGET_REGION_END GLINT_PRAGMA(GCC pop_options)
#endif
