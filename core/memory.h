// Process-wide memory policy for the executables (called once from main, before any work).
#pragma once

#include <cstddef>

namespace glarecam {

// glibc maps each allocation above its mmap threshold (dynamic, 128 KiB to 32 MiB) afresh and
// unmaps it when freed, and trims the heap's free top above its trim threshold: every frame,
// float image and encoded file of a stack then costs a page fault per 4 KiB, and again for the
// next stack. Measured on a 5 MP `process` (2 cores): 85 000 minor faults, 0.73 s of system
// time, 1.40 s wall; with these thresholds 66 000, 0.56 s and 1.18 s, for a peak resident
// size of 292 MB instead of 262 MB.
inline constexpr std::size_t kReusedAllocationMaxBytes = 64u << 20;  // a 12 MP float image: 48 MB
inline constexpr std::size_t kRetainedFreeHeapBytes = 256u << 20;    // about one 5 MP stack's work

// Sets those thresholds (mallopt); false when the C library refuses them (not glibc's malloc).
bool reuseLargeAllocations();

// Blocks at least this large are backed by transparent huge pages where the kernel offers them
// on request (/sys/kernel/mm/transparent_hugepage/enabled "madvise", Debian's default): a 2 MiB
// page faults in once instead of 512 times. Measured on a 5 MP `process`: 49 000 -> 17 000
// minor faults, system time about halved.
inline constexpr std::size_t kHugePageAdviceMinBytes = 4u << 20;
inline constexpr std::size_t kHugePageBytes = 2u << 20;  // x86-64 and arm64 with 4 KiB pages

// Asks for huge pages over the whole 2 MiB pages inside [block, block + bytes) when bytes is at
// least kHugePageAdviceMinBytes (madvise MADV_HUGEPAGE); a refusal changes nothing but speed.
void adviseHugePages(void* block, std::size_t bytes);

}  // namespace glarecam
