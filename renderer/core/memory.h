#pragma once
// How much memory the machine can still give, for checks that refuse an oversized frame or
// input image before allocating it (render_job.cpp, film/image_limits.cpp), and how much this
// process has used (render statistics).
#include <cstdint>
#include <string>

namespace glint {

// MemAvailable of /proc/meminfo (Linux: what can be allocated without swapping), 0 if unknown.
uint64_t availableMemoryBytes();

// The process's peak resident set so far (getrusage's ru_maxrss), in bytes.
uint64_t peakResidentBytes();

// "6.4 GB", for messages.
std::string gigabytes(double bytes);

}  // namespace glint
