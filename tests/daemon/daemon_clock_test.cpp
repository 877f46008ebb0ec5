// The daemon's clocks: a time lapse runs the wall clock faster than the steady clock.
#include "daemon/daemon_clock.h"

#include <gtest/gtest.h>

#include <chrono>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::utc;

TEST(DaemonClock, TimeLapseRunsTheWallClockFaster) {
  const UtcTime start = utc("2026-06-21T05:00:00Z");
  const TimeLapseClock clock(start, 600.0);
  const UtcTime later = start + 1h;
  // An hour of simulated sun is 6 s of real time.
  const auto real = clock.steadyAt(later) - clock.steadyAt(start);
  EXPECT_NEAR(std::chrono::duration<double>(real).count(), 6.0, 1e-6);
  EXPECT_TRUE(clock.clockStatus().synchronised);
  EXPECT_GE(clock.utcNow(), start);
}

}  // namespace
}  // namespace glarecam::daemon
