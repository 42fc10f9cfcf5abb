#include "core/cpu_features.h"

#include <utility>

namespace glint {

std::string cpuFeatureNames(const CpuFeatures& f) {
  std::string names = "x86-64";
  const std::pair<bool, const char*> features[] = {{f.avx2, "AVX2"},
                                                   {f.fma, "FMA"},
                                                   {f.avx512f, "AVX-512F"},
                                                   {f.avx512dq, "AVX-512DQ"},
                                                   {f.avx512vl, "AVX-512VL"}};
  for (const auto& [has, name] : features)
    if (has) names += std::string(", ") + name;
  return names;
}

}  // namespace glint
