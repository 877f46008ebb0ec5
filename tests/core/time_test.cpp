// UTC to the microsecond: utcNow() is the system clock's now at that resolution.
#include "core/time.h"

#include <gtest/gtest.h>

#include <chrono>
#include <type_traits>

namespace glarecam {
namespace {

TEST(Time, UtcIsCountedInMicroseconds) {
  EXPECT_TRUE((std::is_same_v<UtcTime::duration, std::chrono::microseconds>));
  EXPECT_TRUE((std::is_same_v<UtcTime::clock, std::chrono::system_clock>));
}

TEST(Time, UtcNowIsTheSystemClocksNowTruncatedToTheMicrosecond) {
  const auto before = std::chrono::system_clock::now();
  const UtcTime now = utcNow();
  const auto after = std::chrono::system_clock::now();
  EXPECT_LE(before - std::chrono::microseconds(1), now);
  // Truncated, never rounded up past the system clock's reading.
  EXPECT_LE(now, after);
}

}  // namespace
}  // namespace glarecam
