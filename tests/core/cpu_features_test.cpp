// The instruction sets this CPU runs (core/cpu_features.h), read a second way.
#include "core/cpu_features.h"

#include <cpuid.h>
#include <gtest/gtest.h>

#include <cstdint>

#include "core/sin_cos.h"

namespace glint {
namespace {

// The x86 manuals' reading: a feature's CPUID bit, and for AVX and AVX-512 also the register
// state the operating system saves on a switch (XCR0), without which the CPU's support is of
// no use; libgcc's __builtin_cpu_supports asks the same.
struct CpuidReading {
  bool avx2 = false, fma = false, avx512f = false, avx512dq = false, avx512vl = false;
};

CpuidReading readCpuid() {
  CpuidReading r;
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return r;
  const bool osSavesState = (c >> 27) & 1;  // OSXSAVE: XGETBV may be executed
  if (!osSavesState) return r;
  uint32_t xcr0Low = 0, xcr0High = 0;
  __asm__("xgetbv" : "=a"(xcr0Low), "=d"(xcr0High) : "c"(0));
  const bool avxState = (xcr0Low & 0x6) == 0x6;       // XMM and YMM halves
  const bool avx512State = (xcr0Low & 0xe6) == 0xe6;  // and opmasks, ZMM halves, ZMM16-31
  r.fma = avxState && ((c >> 12) & 1);
  if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return r;
  r.avx2 = avxState && ((b >> 5) & 1);
  r.avx512f = avx512State && ((b >> 16) & 1);
  r.avx512dq = avx512State && ((b >> 17) & 1);
  r.avx512vl = avx512State && ((b >> 31) & 1);
  return r;
}

TEST(CpuFeatures, AgreeWithCpuidAndTheOperatingSystemsSavedState) {
  // Each flag is exactly the CPUID bit and the saved state: a flag set wrongly runs AVX code
  // where it faults, one cleared wrongly silently takes the narrower lanes.
  const CpuidReading expected = readCpuid();
  EXPECT_EQ(cpuFeatures().avx2, expected.avx2);
  EXPECT_EQ(cpuFeatures().fma, expected.fma);
  EXPECT_EQ(cpuFeatures().avx512f, expected.avx512f);
  EXPECT_EQ(cpuFeatures().avx512dq, expected.avx512dq);
  EXPECT_EQ(cpuFeatures().avx512vl, expected.avx512vl);
  // What was read at load is what reading again gives.
  const CpuFeatures again = readCpuFeatures();
  EXPECT_EQ(again.avx2, cpuFeatures().avx2);
  EXPECT_EQ(again.avx512f, cpuFeatures().avx512f);
}

TEST(CpuFeatures, TheSamplersAvx512NeedsFDqAndVl) {
  // drawSetRunIn16 is built for all three: a CPU lacking any one (Knights Landing has F but
  // neither DQ nor VL) draws in eight lanes.
  CpuFeatures f;
  f.avx512f = f.avx512dq = true;
  EXPECT_FALSE(f.avx512FDqVl());
  f.avx512vl = true;
  EXPECT_TRUE(f.avx512FDqVl());
  f.avx512f = false;
  EXPECT_FALSE(f.avx512FDqVl());
  const CpuidReading r = readCpuid();
  EXPECT_EQ(cpuFeatures().avx512FDqVl(), r.avx512f && r.avx512dq && r.avx512vl);
}

TEST(CpuFeatures, AreNamedAfterTheBaseline) {
  // What `glint info` prints: the baseline, then each feature set in the usual name.
  CpuFeatures f;
  EXPECT_EQ(cpuFeatureNames(f), "x86-64");
  f.avx2 = f.fma = true;
  EXPECT_EQ(cpuFeatureNames(f), "x86-64, AVX2, FMA");
  f.avx512f = f.avx512dq = f.avx512vl = true;
  EXPECT_EQ(cpuFeatureNames(f), "x86-64, AVX2, FMA, AVX-512F, AVX-512DQ, AVX-512VL");
  f.avx2 = f.avx512dq = false;
  EXPECT_EQ(cpuFeatureNames(f), "x86-64, FMA, AVX-512F, AVX-512VL");
}

TEST(CpuFeatures, AreReadBeforeAConstantComputedFromThemAtLoad) {
  // sinCos decides at load, among static constructors, whether its lanes run: from these
  // flags, then by comparing sixteen probes with glibc (2.28 or later gives its FMA build's
  // floats, which the lanes repeat). Read before they were set, the flags would be all false
  // and the lanes off on every CPU.
#if defined(__GLIBC__) && __GLIBC_PREREQ(2, 28)
  if (!cpuFeatures().fma || !cpuFeatures().avx2) GTEST_SKIP() << "no FMA and AVX2 on this CPU";
  EXPECT_TRUE(sinCosInLanes());
#else
  GTEST_SKIP() << "not glibc 2.28 or later: sinCos may keep to the C library";
#endif
}

}  // namespace
}  // namespace glint
