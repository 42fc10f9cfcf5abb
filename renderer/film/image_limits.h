#pragma once
// Bounds on the images Glint reads (glint compare, convert, converge --reference, merge). An
// EXR's header declares its data window; reading it allocates window × channels values, so a
// 50 MB RLE file declaring a huge window took 6.4 GB before it failed. Every reader checks the
// declared size here first and refuses, naming the file, what would not fit.
#include <cstdint>
#include <string>

namespace glint {

// Throws UsageError naming `path` when `width` × `height` pixels of `bytesPerPixel` bytes are
// not a positive size, or need more than the budget (imageMemoryBudget()). `what` says which
// window: "data window", "display window".
void checkImageFits(const std::string& path, const std::string& what, int64_t width, int64_t height,
                    double bytesPerPixel);

// The bytes one image read may take: MemAvailable (core/memory.h), unless set below; 0 means
// unknown (then only the size must be positive and addressable).
uint64_t imageMemoryBudget();
// Sets the budget for this process (0: MemAvailable again). The fuzzer sets 1 GB, below its own
// allocation limit, so that what Glint accepts never trips that limit.
void setImageMemoryBudget(uint64_t bytes);

}  // namespace glint
