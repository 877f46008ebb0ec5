#include "core/memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>

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

}  // namespace
}  // namespace glarecam
