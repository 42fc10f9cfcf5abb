#pragma once
// The instruction sets beyond baseline x86-64 that this CPU runs, read once: the choices of code
// Glint makes itself (the lanes of intersectLanes, the sampler's width, sinCos, the environment's
// searches, GLINT_AVX2_CLONES under Clang with LTO) read them here; target_clones' copies are
// chosen by the loader from the same CPUID bits.
#include <string>

namespace glint {

struct CpuFeatures {
  bool avx2 = false, fma = false;
  bool avx512f = false, avx512dq = false, avx512vl = false;
  // AVX-512 F, DQ (64-bit multiplies) and VL (their 128- and 256-bit forms): what the sampler's
  // sixteen lanes are built for.
  bool avx512FDqVl() const { return avx512f && avx512dq && avx512vl; }
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

// The features, read at the first call: a constant computed from them at load (sinCos's check
// of its lanes, the sampler's width), in any file, then sees them set. An inline variable does
// not promise that: GCC ordered its initialiser before a file's own, but Clang runs it apart
// (an ASan build drew in eight lanes on an AVX-512 CPU).
inline const CpuFeatures& cpuFeatures() {
  static const CpuFeatures features = readCpuFeatures();
  return features;
}

// The features `f` has, by their usual names after the baseline: "x86-64, AVX2, FMA, AVX-512F,
// AVX-512DQ, AVX-512VL" where it has all of them (`glint info` prints it).
std::string cpuFeatureNames(const CpuFeatures& f);

}  // namespace glint
