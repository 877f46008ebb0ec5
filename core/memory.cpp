#include "core/memory.h"

#include <malloc.h>

namespace glarecam {

bool reuseLargeAllocations() {
  // Setting either disables glibc's dynamic threshold; both are needed (only the mmap threshold:
  // freed blocks return to the heap and are trimmed away at once).
  return mallopt(M_MMAP_THRESHOLD, static_cast<int>(kReusedAllocationMaxBytes)) == 1 &&
         mallopt(M_TRIM_THRESHOLD, static_cast<int>(kRetainedFreeHeapBytes)) == 1;
}

}  // namespace glarecam
