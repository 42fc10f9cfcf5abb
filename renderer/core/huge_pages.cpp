#include "core/huge_pages.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>

namespace glint {

namespace {

constexpr std::align_val_t kHugePageAlignment{kHugePageBytes};

size_t roundedToHugePages(size_t bytes) {
  return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

}  // namespace

void* allocateBuffer(size_t bytes) {
  if (bytes < kHugePageBytes) return ::operator new(bytes);
  if (bytes > SIZE_MAX - kHugePageBytes) throw std::bad_alloc();  // its rounding would wrap
  const size_t size = roundedToHugePages(bytes);
  void* p = ::operator new(size, kHugePageAlignment);
#ifdef MADV_HUGEPAGE
  // Advice only: where the kernel has no huge pages to lend, the buffer takes small ones.
  (void)::madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

void freeBuffer(void* p, size_t bytes) noexcept {
  // Unsized: Clang takes sized deallocation only with -fsized-deallocation.
  if (bytes < kHugePageBytes)
    ::operator delete(p);
  else
    ::operator delete(p, kHugePageAlignment);
}

}  // namespace glint
