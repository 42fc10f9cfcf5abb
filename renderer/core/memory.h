#pragma once
// How much memory this process can still take, for checks that refuse an oversized frame,
// input image, texture or scene before allocating it (render_job.cpp, film/image_limits.cpp,
// io/texture_file.cpp, app/scene_source.cpp), and how much it has used (render statistics).
// The budget is the least of three sources (core/memory_sources.h): the machine's
// MemAvailable, the address-space limit (RLIMIT_AS) less what is mapped, and the memory
// cgroup's limit less its usage.
#include <cstdint>
#include <string>

#include "core/memory_sources.h"

namespace glint {

// The budget now, and which source sets it.
MemoryBudget currentMemoryBudget();

// currentMemoryBudget()'s bytes: 0 if no source is known.
uint64_t availableMemoryBytes();

// "the 380 MB of address space that the limit (ulimit -v, RLIMIT_AS) leaves", for messages.
std::string describeBudget(const MemoryBudget& budget);

// Throws OutOfMemoryError (core/error.h) "out of memory: WHAT needs N MB, more than <the
// budget>" when `bytes` exceed the current budget; does nothing when the budget is unknown.
void checkMemoryFits(double bytes, const std::string& what);

// The process's peak resident set so far (getrusage's ru_maxrss), in bytes.
uint64_t peakResidentBytes();

// "6.4 GB", for messages.
std::string gigabytes(double bytes);
// "380 MB" below a gigabyte, else as gigabytes(): limits of a few hundred MB stay readable.
std::string memorySize(double bytes);

}  // namespace glint
