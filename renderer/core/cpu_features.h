#pragma once
// The instruction sets beyond baseline x86-64 that this CPU runs, read once when the program
// loads: every choice of code built for one (the lanes of intersectLanes, the sampler, sinCos,
// the environment's searches) reads them here.

namespace glint {

struct CpuFeatures {
  bool avx2 = false, fma = false;
  bool avx512f = false, avx512dq = false, avx512vl = false;
};

// __builtin_cpu_init first: this may run among static constructors, before libgcc's own.
inline CpuFeatures readCpuFeatures() {
  __builtin_cpu_init();
  CpuFeatures f;
  f.avx2 = __builtin_cpu_supports("avx2");
  f.fma = __builtin_cpu_supports("fma");
  f.avx512f = __builtin_cpu_supports("avx512f");
  f.avx512dq = __builtin_cpu_supports("avx512dq");
  f.avx512vl = __builtin_cpu_supports("avx512vl");
  return f;
}

// An inline variable, so that a file's own constants read from it at load (sinCos's check of
// its lanes) are initialised after it: C++17 orders an inline variable before every variable
// defined after it in each file that defines both.
inline const CpuFeatures kCpuFeatures = readCpuFeatures();

}  // namespace glint
