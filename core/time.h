// An instant in UTC to the microsecond, the time every stack, sun position and schedule uses,
// the system clock's now as one, and its whole seconds as text. Parsing ISO 8601 (zones,
// fractions) is sun/utc_time.h's.
#pragma once

#include <chrono>
#include <string>

namespace glarecam {

using UtcTime = std::chrono::sys_time<std::chrono::microseconds>;

// The system clock now (whether it can be trusted is sun/clock_sync.h's question).
inline UtcTime utcNow() {
  return std::chrono::time_point_cast<std::chrono::microseconds>(std::chrono::system_clock::now());
}

// `time`'s whole seconds in UTC through strftime(3)'s `format`: "%Y-%m-%dT%H:%M:%SZ" (a
// manifest's captured_at), "%Y%m%dT%H%M%SZ" (a stack's id).
std::string formatUtc(UtcTime time, const char* format);

}  // namespace glarecam
