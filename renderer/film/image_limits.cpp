#include "film/image_limits.h"

#include <atomic>
#include <cstdio>

#include "core/error.h"
#include "core/memory.h"

namespace glint {

namespace {
std::atomic<uint64_t> gBudget{0};
}  // namespace

uint64_t imageMemoryBudget() {
  const uint64_t set = gBudget.load();
  return set != 0 ? set : availableMemoryBytes();
}

void setImageMemoryBudget(uint64_t bytes) { gBudget.store(bytes); }

void checkImageFits(const std::string& path, const std::string& what, int64_t width, int64_t height,
                    double bytesPerPixel) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width <= 0 || height <= 0 || !(bytesPerPixel > 0))
    throw UsageError(path + ": its " + what + " " + size + " is empty");
  // In double: the product of two 31-bit sides and a pixel size may not fit 64 bits.
  const double needed = double(width) * double(height) * bytesPerPixel;
  const uint64_t budget = imageMemoryBudget();
  // 2^62 bytes bounds every size_t product the readers form, whatever the budget.
  if (needed > 0x1p62 || (budget != 0 && needed > double(budget)))
    throw UsageError(path + ": its " + what + " " + size + " needs " + gigabytes(needed) +
                     " to read, more than " +
                     (budget != 0 ? "the " + gigabytes(double(budget)) + " of memory available"
                                  : std::string("a process can address")));
}

}  // namespace glint
