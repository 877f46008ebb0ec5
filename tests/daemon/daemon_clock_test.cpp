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

// The sun moves 0.01° in a real bracket: a simulated one must not move it 120 times as far.
TEST(DaemonClock, AStacksTimeLineRunsAtRealRateOnATimeLapse) {
  testing::ManualClock steady(utc("2026-06-21T08:00:00Z"));
  const UtcTime start = utc("2026-06-21T05:00:00Z");
  const TimeLapseClock clock(start, 120.0, steady);
  const StackTimeline timeline(clock);
  steady.advance(2s);  // the bracket
  EXPECT_EQ(timeline.begun(), start);
  EXPECT_EQ(timeline.now(), start + 2s);
  EXPECT_EQ(clock.utcNow(), start + 240s);  // the time lapse itself runs on
}

TEST(DaemonClock, AStacksTimeLineIsTheWallClockElsewhere) {
  testing::ManualClock clock(utc("2026-06-21T08:00:00Z"));
  const StackTimeline timeline(clock);
  clock.advance(2s);
  EXPECT_EQ(timeline.begun(), utc("2026-06-21T08:00:00Z"));
  EXPECT_EQ(timeline.now(), clock.utcNow());
}

}  // namespace
}  // namespace glarecam::daemon
