#include "core/memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "core/build_config.h"
#include "core/image.h"

namespace glarecam {
namespace {

// Writes every byte where the compiler cannot drop the writes (or the allocation with them).
void touch(void* block, std::size_t bytes, int value) {
  std::memset(block, value, bytes);
  asm volatile("" : : "r"(block) : "memory");
}

long minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// A large block freed and allocated again is the same memory, not a fresh mapping that faults in
// page by page: 40 MB are 10 240 pages of 4 KiB; reused, touching them again faults at most a few
// (the bound leaves room for anything else the process touches meanwhile).
TEST(Memory, LargeBlocksAreReusedWithoutFaultingAgain) {
  if (!reuseLargeAllocations()) GTEST_SKIP() << "this malloc refuses mallopt (a sanitizer's?)";
  constexpr std::size_t kBytes = 40u << 20;
  constexpr long kPages = kBytes / 4096;
  void* first = std::malloc(kBytes);
  ASSERT_NE(first, nullptr);
  touch(first, kBytes, 1);
  std::free(first);
  const long before = minorFaults();
  void* again = std::malloc(kBytes);
  ASSERT_NE(again, nullptr);
  touch(again, kBytes, 2);
  const long faults = minorFaults() - before;
  std::free(again);
  EXPECT_LT(faults, kPages / 10) << "a fresh mapping faults once per page: " << kPages;
}

// Where the kernel gives transparent huge pages on request, a large image faults in 2 MiB at a
// time: a fresh 16 MiB image (4096 pages of 4 KiB) faults far fewer than 4096 times as it is
// filled. The block need not start on a 2 MiB boundary: its ragged ends, together up to 2 MiB,
// fault page by page (512), the 7 or 8 whole huge pages once each; the bound is 4096 / 4. In a
// fresh process (a "threadsafe" death test re-runs the binary), whose allocator has no freed memory
// to hand back.
TEST(MemoryDeathTest, LargeImagesFaultInHugePages) {
#if GLARECAM_SANITIZE
  GTEST_SKIP() << "under AddressSanitizer its shadow memory faults page by page besides";
#endif
  std::ifstream enabled("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(enabled, modes);
  if (modes.find("[never]") != std::string::npos || modes.empty())
    GTEST_SKIP() << "transparent huge pages are off here: " << modes;
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const long before = minorFaults();
        const FloatImage image(2048, 2048, 1.0f);
        const long faults = minorFaults() - before;
        std::fprintf(stderr, "%s faults\n",
                     faults < 4096 / 4 ? "few" : std::to_string(faults).c_str());
        std::exit(image.at(5, 5) == 1.0f ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "few faults");
}

}  // namespace
}  // namespace glarecam
