#include "core/memory.h"

#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>

namespace glarecam {

bool reuseLargeAllocations() {
  // Setting either disables glibc's dynamic threshold; both are needed (only the mmap threshold:
  // freed blocks return to the heap and are trimmed away at once).
  return mallopt(M_MMAP_THRESHOLD, static_cast<int>(kReusedAllocationMaxBytes)) == 1 &&
         mallopt(M_TRIM_THRESHOLD, static_cast<int>(kRetainedFreeHeapBytes)) == 1;
}

void adviseHugePages(void* block, std::size_t bytes) {
  if (bytes < kHugePageAdviceMinBytes) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t first = (begin + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  const std::uintptr_t last = (begin + bytes) / kHugePageBytes * kHugePageBytes;
  if (last > first)
    madvise(reinterpret_cast<void*>(first), last - first,
            MADV_HUGEPAGE);  // only speed depends on it
}

}  // namespace glarecam
