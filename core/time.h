// An instant in UTC to the microsecond, the time every stack, sun position and schedule uses,
// and the system clock's now as one. Text in ISO 8601 is sun/utc_time.h's.
#pragma once

#include <chrono>

namespace glarecam {

using UtcTime = std::chrono::sys_time<std::chrono::microseconds>;

// The system clock now (whether it can be trusted is sun/clock_sync.h's question).
inline UtcTime utcNow() {
  return std::chrono::time_point_cast<std::chrono::microseconds>(std::chrono::system_clock::now());
}

}  // namespace glarecam
