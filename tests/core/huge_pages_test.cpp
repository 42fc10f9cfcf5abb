// A frame's large buffers on transparent huge pages (core/huge_pages.h): blocks of 2 MiB and
// more are aligned to a huge page and advised so, to their last byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/huge_pages.h"
#include "core/unwritten_allocator.h"

namespace glint {
namespace {

// The kernel's VmFlags of the mapping that holds `p` (/proc/self/smaps), e.g. "rd wr mr mw me
// ac hg": "hg" is MADV_HUGEPAGE.
std::string vmFlagsAt(const void* p) {
  const auto address = reinterpret_cast<uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= address && address < end;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line.substr(8) + " ";
  }
  return "";
}

bool kernelHasHugePages() {
  return std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled");
}

TEST(HugePages, LargeBuffersAreAlignedAndAdvisedAsHugePages) {
  if (!kernelHasHugePages())
    GTEST_SKIP() << "this kernel has no transparent huge pages: nothing to advise";
  const size_t bytes = 3 * kHugePageBytes + 100;  // not a whole number of huge pages
  void* p = allocateBuffer(bytes);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % kHugePageBytes, 0u);
  std::memset(p, 1, bytes);  // every byte is the caller's
  // The last byte's page is advised too: the advice covers the rounded-up block.
  EXPECT_NE(vmFlagsAt(p).find(" hg "), std::string::npos) << vmFlagsAt(p);
  EXPECT_NE(vmFlagsAt(static_cast<char*>(p) + bytes - 1).find(" hg "), std::string::npos);
  freeBuffer(p, bytes);
}

TEST(HugePages, UnwrittenVectorsOfAFrameTakeHugePages) {
  if (!kernelHasHugePages())
    GTEST_SKIP() << "this kernel has no transparent huge pages: nothing to advise";
  // A 512 x 512 frame's RGBA in double, as the film keeps it.
  std::vector<double, UnwrittenAllocator<double>> rgba(size_t{512} * 512 * 4);
  rgba.back() = 1;
  EXPECT_EQ(reinterpret_cast<uintptr_t>(rgba.data()) % kHugePageBytes, 0u);
  EXPECT_NE(vmFlagsAt(rgba.data()).find(" hg "), std::string::npos);
}

}  // namespace
}  // namespace glint
