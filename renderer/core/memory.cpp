#include "core/memory.h"

#include <sys/resource.h>

#include <cstdio>

#include "core/error.h"

namespace glint {

MemoryBudget currentMemoryBudget() { return memoryBudget(readMemoryReadings()); }

uint64_t availableMemoryBytes() { return currentMemoryBudget().bytes; }

std::string describeBudget(const MemoryBudget& budget) {
  const std::string size = "the " + memorySize(double(budget.bytes));
  switch (budget.limitedBy) {
    case MemoryLimit::Available:
      return size + " of memory available";
    case MemoryLimit::AddressSpace:
      return size + " of address space that the limit (ulimit -v, RLIMIT_AS) leaves";
    case MemoryLimit::Cgroup:
      return size + " that the memory cgroup's limit leaves";
    case MemoryLimit::Unknown:
      break;
  }
  return "what a process can address";
}

void checkMemoryFits(double bytes, const std::string& what) {
  const MemoryBudget budget = currentMemoryBudget();
  if (budget.limitedBy == MemoryLimit::Unknown || !(bytes > double(budget.bytes))) return;
  throw OutOfMemoryError("out of memory: " + what + " needs " + memorySize(bytes) + ", more than " +
                         describeBudget(budget));
}

std::string gigabytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GB", bytes * 1e-9);
  return buf;
}

std::string memorySize(double bytes) {
  if (bytes >= 1e9) return gigabytes(bytes);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MB", bytes * 1e-6);
  return buf;
}

uint64_t peakResidentBytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace glint
