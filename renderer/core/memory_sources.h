#pragma once
// Where the memory budget (core/memory.h) comes from: the machine's MemAvailable, the
// address-space limit (RLIMIT_AS, `ulimit -v`, `prlimit --as`) less what the process has mapped,
// and the memory cgroup's limit less its usage. Each is parsed from the text of its /proc or
// /sys file by a pure function, so that the arithmetic is tested with any values.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

// Which source sets the budget: the one that leaves the least.
enum class MemoryLimit { Unknown, Available, AddressSpace, Cgroup };

// What the sources read; absent where a source is unknown or sets no limit.
struct MemoryReadings {
  std::optional<uint64_t> available;          // MemAvailable
  std::optional<uint64_t> addressSpaceLimit;  // RLIMIT_AS's soft limit
  uint64_t addressSpaceUsed = 0;              // VmSize
  std::optional<uint64_t> cgroupHeadroom;     // least limit − usage over the cgroup's ancestry
};

struct MemoryBudget {
  uint64_t bytes = 0;  // 0: no source is known
  MemoryLimit limitedBy = MemoryLimit::Unknown;
};

// The least of the sources. A source with nothing left gives 1 byte, not 0 (which would read
// as unknown), so every check against it refuses.
MemoryBudget memoryBudget(const MemoryReadings& readings);

// "MemAvailable:   22919 kB" of /proc/meminfo, in bytes.
std::optional<uint64_t> parseMemAvailable(std::string_view meminfo);
// "VmSize:   3760 kB" of /proc/self/status, in bytes.
std::optional<uint64_t> parseVmSize(std::string_view status);

// The directories holding the process's memory-cgroup files, innermost first, then each
// ancestor up to the mount: those of cgroup v2 (`0::PATH` under a cgroup2 mount), then those of
// v1's memory controller (`N:...memory...:PATH` under a cgroup mount with the memory option).
// `cgroup` is /proc/self/cgroup, `mountinfo` /proc/self/mountinfo.
struct CgroupDir {
  std::string path;
  bool v2 = true;
};
std::vector<CgroupDir> memoryCgroupDirs(std::string_view cgroup, std::string_view mountinfo);

// A cgroup's limit less its usage, from the text of memory.max and memory.current (v2) or
// memory.limit_in_bytes and memory.usage_in_bytes (v1); absent when it sets no limit ("max",
// or v1's "unlimited" of about 2^63) or the text is not a number.
std::optional<uint64_t> cgroupHeadroom(std::string_view limit, std::string_view usage);

// The readings of this process, now.
MemoryReadings readMemoryReadings();

}  // namespace glint
