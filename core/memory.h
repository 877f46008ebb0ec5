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

}  // namespace glarecam
