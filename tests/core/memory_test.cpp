// The memory budget (core/memory.h, core/memory_sources.h): each source parsed from the text of
// its file, the least of them taken, and the real address-space limit honoured in a child
// process; running out of memory named as what was being done (core/out_of_memory.h).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/child_process.h"
#include "core/memory.h"
#include "core/memory_sources.h"
#include "core/out_of_memory.h"
#include "test_util.h"

namespace glint {
namespace {

constexpr uint64_t kMB = uint64_t{1} << 20;

TEST(MemoryBudget, TheLeastSourceSetsTheBudgetAndIsNamed) {
  MemoryReadings r;
  r.available = 8000 * kMB;
  EXPECT_EQ(memoryBudget(r).bytes, 8000 * kMB);
  EXPECT_EQ(memoryBudget(r).limitedBy, MemoryLimit::Available);
  // 500 MB of address space with 120 MB mapped leaves 380 MB, below the 8000 available.
  r.addressSpaceLimit = 500 * kMB;
  r.addressSpaceUsed = 120 * kMB;
  EXPECT_EQ(memoryBudget(r).bytes, 380 * kMB);
  EXPECT_EQ(memoryBudget(r).limitedBy, MemoryLimit::AddressSpace);
  // A cgroup with 200 MB left is tighter still.
  r.cgroupHeadroom = 200 * kMB;
  EXPECT_EQ(memoryBudget(r).bytes, 200 * kMB);
  EXPECT_EQ(memoryBudget(r).limitedBy, MemoryLimit::Cgroup);
  // A process mapped past its limit has nothing left: 1 byte, which every check refuses (0
  // would read as "unknown").
  r.addressSpaceUsed = 600 * kMB;
  EXPECT_EQ(memoryBudget(r).bytes, 1u);
  EXPECT_EQ(memoryBudget(r).limitedBy, MemoryLimit::AddressSpace);
  // No source known: no budget, and no check refuses.
  EXPECT_EQ(memoryBudget(MemoryReadings{}).bytes, 0u);
  EXPECT_EQ(memoryBudget(MemoryReadings{}).limitedBy, MemoryLimit::Unknown);
}

TEST(MemoryBudget, ProcFilesAreParsedInKilobytes) {
  const std::string meminfo =
      "MemTotal:       24684600 kB\nMemFree:        21334016 kB\n"
      "MemAvailable:   23469056 kB\nBuffers:          123 kB\n";
  EXPECT_EQ(parseMemAvailable(meminfo), uint64_t{23469056} * 1024);
  EXPECT_EQ(parseMemAvailable("MemTotal: 5 kB\n"), std::nullopt);
  const std::string status = "Name:\tglint\nVmPeak:\t   80000 kB\nVmSize:\t   74712 kB\n";
  EXPECT_EQ(parseVmSize(status), uint64_t{74712} * 1024);
  EXPECT_EQ(parseVmSize("VmSize:\t  12 MB\n"), std::nullopt);  // not the kernel's unit
}

TEST(MemoryBudget, CgroupHeadroomIsLimitLessUsage) {
  EXPECT_EQ(cgroupHeadroom("1073741824\n", "268435456\n"), uint64_t{768} * kMB);
  EXPECT_EQ(cgroupHeadroom("max\n", "268435456\n"), std::nullopt);  // v2: no limit
  // v1 writes "no limit" as the largest page multiple below 2^63.
  EXPECT_EQ(cgroupHeadroom("9223372036854771712\n", "3027062784\n"), std::nullopt);
  EXPECT_EQ(cgroupHeadroom("100\n", "150\n"), 0u);  // over its limit (reclaim pending)
  EXPECT_EQ(cgroupHeadroom("", ""), std::nullopt);  // the files do not exist
}

TEST(MemoryBudget, CgroupDirectoriesComeFromProcSelfCgroupAndMountinfo) {
  // A pure cgroup v2 host: the process's cgroup and each ancestor to the mount point.
  const std::string v2Mounts =
      "25 30 0:23 / /sys/fs/cgroup rw,nosuid - cgroup2 cgroup2 rw,nsdelegate\n";
  const auto v2 = memoryCgroupDirs("0::/user.slice/job 7\n", v2Mounts);
  ASSERT_EQ(v2.size(), 3u);
  EXPECT_EQ(v2[0].path, "/sys/fs/cgroup/user.slice/job 7");
  EXPECT_EQ(v2[1].path, "/sys/fs/cgroup/user.slice");
  EXPECT_EQ(v2[2].path, "/sys/fs/cgroup");
  EXPECT_TRUE(v2[0].v2);
  // A hybrid host (this project's machines): v2 mounted at unified/ holding the root cgroup,
  // and v1's memory controller, whose cgroup is the one with the limit.
  const std::string hybridMounts =
      "31 23 0:28 / /sys/fs/cgroup rw,relatime - tmpfs tmpfs rw,mode=755\n"
      "34 31 0:31 / /sys/fs/cgroup/cpuset rw,relatime - cgroup cgroup rw,cpuset\n"
      "35 31 0:32 / /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory\n"
      "41 31 0:38 / /sys/fs/cgroup/unified rw,relatime - cgroup2 cgroup2 rw\n";
  const std::string hybridCgroup = "5:devices:/\n4:memory:/process_api/2ff8\n3:cpuset:/\n0::/\n";
  const auto hybrid = memoryCgroupDirs(hybridCgroup, hybridMounts);
  ASSERT_EQ(hybrid.size(), 4u);
  EXPECT_EQ(hybrid[0].path, "/sys/fs/cgroup/unified");
  EXPECT_TRUE(hybrid[0].v2);
  EXPECT_EQ(hybrid[1].path, "/sys/fs/cgroup/memory/process_api/2ff8");
  EXPECT_FALSE(hybrid[1].v2);
  EXPECT_EQ(hybrid[3].path, "/sys/fs/cgroup/memory");
  // A container whose mount shows a subtree (root /docker/abc): paths inside it lose the
  // prefix; a space in a mount point is written \040.
  const std::string containerMounts =
      "50 40 0:40 /docker/abc /sys/fs/my\\040cg ro - cgroup2 cgroup2 rw\n";
  const auto inside = memoryCgroupDirs("0::/docker/abc/task\n", containerMounts);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_EQ(inside[0].path, "/sys/fs/my cg/task");
  EXPECT_EQ(inside[1].path, "/sys/fs/my cg");
  // A cgroup outside the mount's subtree cannot be read there: the mount point stands for it.
  const auto outside = memoryCgroupDirs("0::/elsewhere\n", containerMounts);
  ASSERT_EQ(outside.size(), 1u);
  EXPECT_EQ(outside[0].path, "/sys/fs/my cg");
  EXPECT_TRUE(memoryCgroupDirs("", v2Mounts).empty());
}

TEST(MemoryBudget, TheAddressSpaceLimitOfTheProcessIsHonoured) {
  if (test::kAddressSanitizer)
    GTEST_SKIP() << "under AddressSanitizer a process cannot run below an address-space limit";
  // A child limited to what it has mapped plus 64 MB: its budget is at most those 64 MB (what it
  // maps meanwhile comes off), set by the address space; 512 MB is refused naming that limit.
  const auto [status, text] = test::inChild([] {
    std::ifstream in("/proc/self/status");
    const std::string procStatus((std::istreambuf_iterator<char>(in)), {});
    const uint64_t used = parseVmSize(procStatus).value_or(0);
    const rlimit limit{rlim_t(used + 64 * kMB), rlim_t(used + 64 * kMB)};
    if (used == 0 || ::setrlimit(RLIMIT_AS, &limit) != 0) return 3;
    const MemoryBudget budget = currentMemoryBudget();
    std::fprintf(stderr, "budget %llu source %d\n", (unsigned long long)budget.bytes,
                 int(budget.limitedBy));
    if (budget.limitedBy != MemoryLimit::AddressSpace) return 4;
    if (budget.bytes > 64 * kMB || budget.bytes < 32 * kMB) return 5;
    if (availableMemoryBytes() > 64 * kMB) return 6;
    try {
      checkMemoryFits(512.0 * double(kMB), "a test's 512 MB");
      return 7;
    } catch (const OutOfMemoryError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return std::string(e.what()).find(
                 "out of memory: a test's 512 MB needs 537 MB, more than "
                 "the ") == 0 &&
                     std::string(e.what()).find("address space") != std::string::npos
                 ? 0
                 : 8;
    }
  });
  EXPECT_EQ(status, 0) << text;
}

TEST(OutOfMemory, AFailedAllocationIsNamedByTheWorkUnderWay) {
  try {
    out_of_memory::whileDoing("reading mesh m.obj", []() -> int { throw std::bad_alloc(); });
    FAIL() << "no exception";
  } catch (const OutOfMemoryError& e) {
    EXPECT_STREQ(e.what(), "out of memory while reading mesh m.obj");
  }
  // pthread_create's EAGAIN (a thread stack beyond RLIMIT_AS) is the same failure.
  try {
    out_of_memory::whileDoing("loading the image module", []() -> int {
      throw std::system_error(EAGAIN, std::generic_category(), "thread");
    });
    FAIL() << "no exception";
  } catch (const OutOfMemoryError& e) {
    EXPECT_STREQ(e.what(), ("out of memory while loading the image module (thread: " +
                            std::error_code(EAGAIN, std::generic_category()).message() + ")")
                               .c_str());
  }
  // So is TBB's runtime_error ending in strerror(EAGAIN).
  EXPECT_THROW(out_of_memory::whileDoing("rendering",
                                         []() -> int {
                                           throw std::runtime_error(
                                               "pthread_create has failed: Resource temporarily "
                                               "unavailable");
                                         }),
               OutOfMemoryError);
  // Other system errors are not memory's.
  EXPECT_THROW(
      out_of_memory::whileDoing(
          "x", []() -> int { throw std::system_error(ENOENT, std::generic_category(), "open"); }),
      std::system_error);
  // The innermost activity names the work for failures no catch reaches.
  {
    const out_of_memory::Activity outer("reading scene s.json");
    const out_of_memory::Activity inner("reading texture t.png");
    EXPECT_EQ(out_of_memory::message(), "out of memory while reading texture t.png");
  }
  EXPECT_EQ(out_of_memory::message(), "out of memory");
}

[[gnu::noinline]] void throwBadAlloc() { throw std::bad_alloc(); }
void throwThroughNoexcept() noexcept { throwBadAlloc(); }

TEST(OutOfMemory, ABadAllocThatReachesTerminateIsExit1NamingTheWork) {
  // nlohmann-json's destructor allocates; a bad_alloc there (or in any noexcept function, or a
  // library's thread) calls std::terminate. With the handler installed that is exit 1 and the
  // message, not SIGABRT.
  const auto [status, text] = test::inChild([] {
    out_of_memory::install();
    const out_of_memory::Activity reading("reading scene big.json");
    throwThroughNoexcept();
    return 0;
  });
  EXPECT_EQ(status, 1) << text;
  EXPECT_EQ(text, "glint: error: out of memory while reading scene big.json\n");
}

TEST(OutOfMemory, ALibraryThatTerminatesWhileOurOutOfMemoryErrorIsHandledIsExit1) {
  // Embree, asked to release a scene it could not build for want of memory, calls
  // std::terminate while the OutOfMemoryError its failure became is being handled.
  const auto [status, text] = test::inChild([] {
    out_of_memory::install();
    try {
      throw OutOfMemoryError("committing the Embree scene: Embree error 4: out of memory");
    } catch (...) {
      std::terminate();
    }
    return 0;
  });
  EXPECT_EQ(status, 1) << text;
  EXPECT_EQ(text, "glint: error: committing the Embree scene: Embree error 4: out of memory\n");
}

}  // namespace
}  // namespace glint
