#pragma once
// Storage for a frame's large buffers (the pixels' estimates, the film, the packed EXR parts),
// on transparent huge pages where the kernel lends them on request (Linux's "madvise" mode,
// Debian's default). Each page's first write costs a page fault, and a frame's buffers span
// thousands of 4 KiB pages where they span a few 2 MiB ones.
#include <cstddef>

namespace glint {

// At least this many bytes are placed on huge pages; smaller blocks come from operator new.
inline constexpr size_t kHugePageBytes = size_t{2} << 20;

// Like operator new (the new-handler runs, std::bad_alloc on failure); free with
// freeBuffer(p, bytes), the same bytes.
void* allocateBuffer(size_t bytes);
void freeBuffer(void* p, size_t bytes) noexcept;

}  // namespace glint
