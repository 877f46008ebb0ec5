// The watchdog as the loop feeds it around brackets, on the manual clock: the bracket estimate
// (the last good bracket and half again, at least its exposures; unknown before the first
// auto-bracket) and the ping sent before a bracket in which one would fall due.
#include "daemon/bracket_watchdog.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;

// WATCHDOG_USEC 10 s: a ping is due every 5 s.
struct WatchedLoop {
  testing::ManualClock clock{testing::utc("2026-06-21T08:00:00Z")};
  testing::RecordingNotifier notifier{clock, 10s};
  testing::ScriptedDisk disk;
  HealthMonitor health{clock, notifier, disk};
  BracketWatchdog watchdog{health};
  WatchedLoop() { health.start(); }
  std::size_t pings() const { return notifier.count("WATCHDOG=1"); }
};

capture::CaptureSettings fixedBracket(std::vector<double> exposures_us) {
  capture::CaptureSettings settings;
  settings.exposures_us = std::move(exposures_us);
  return settings;
}

TEST(BracketWatchdog, BeforeTheFirstBracketItsExposuresOrUnknown) {
  WatchedLoop loop;
  EXPECT_EQ(loop.watchdog.expectedBracket(fixedBracket({1000, 2000, 4000.5})), 7000500ns);
  EXPECT_EQ(loop.watchdog.expectedBracket(capture::CaptureSettings{}), kUnknownBracket);  // auto
  EXPECT_EQ(loop.watchdog.expectedBracket(fixedBracket({})), kUnknownBracket);
}

TEST(BracketWatchdog, TheLastGoodBracketAndHalfAgainAtLeastItsExposures) {
  WatchedLoop loop;
  loop.watchdog.recordBracket(4s);
  EXPECT_EQ(loop.watchdog.expectedBracket(capture::CaptureSettings{}), 6s);
  EXPECT_EQ(loop.watchdog.expectedBracket(fixedBracket({1e6, 2e6})), 6s);
  EXPECT_EQ(loop.watchdog.expectedBracket(fixedBracket({4e6, 3e6})), 7s);  // longer exposures
  loop.watchdog.recordBracket(1s);  // the last one counts, not the longest
  EXPECT_EQ(loop.watchdog.expectedBracket(capture::CaptureSettings{}), 1500ms);
}

// Pings due at 0, 5 s, 10 s, ...: before a bracket expected to end before the next is due, none;
// one expected to end at or after it gets its ping now.
TEST(BracketWatchdog, APingDueDuringTheBracketIsSentBeforeIt) {
  WatchedLoop loop;
  EXPECT_TRUE(loop.watchdog.feed(std::nullopt));
  loop.watchdog.recordBracket(2s);  // expected 3 s
  loop.clock.advance(1s);
  EXPECT_FALSE(loop.watchdog.feedBeforeBracket(capture::CaptureSettings{}, std::nullopt));
  EXPECT_FALSE(loop.watchdog.feed(std::nullopt));
  loop.clock.advance(1s);  // 2 s: the bracket would end as the next ping falls due
  EXPECT_TRUE(loop.watchdog.feedBeforeBracket(capture::CaptureSettings{}, std::nullopt));
  EXPECT_EQ(loop.pings(), 2u);
  EXPECT_EQ(loop.health.nextWatchdog(), loop.clock.now() + 5s);
}

TEST(BracketWatchdog, TheFirstAutoBracketAlwaysGetsAPingAFixedOneByItsExposures) {
  WatchedLoop loop;
  EXPECT_TRUE(loop.watchdog.feed(std::nullopt));
  loop.clock.advance(1s);
  EXPECT_FALSE(loop.watchdog.feedBeforeBracket(fixedBracket({1e6, 2e6}), std::nullopt));
  EXPECT_TRUE(loop.watchdog.feedBeforeBracket(capture::CaptureSettings{}, std::nullopt));
  EXPECT_EQ(loop.pings(), 2u);
}

// A worker job running past kWorkerStallLimit is stuck: no ping, before a bracket either.
TEST(BracketWatchdog, AStuckWorkerGetsNoPing) {
  WatchedLoop loop;
  const SteadyTime busy_since = loop.clock.now();
  loop.clock.advance(kWorkerStallLimit);
  EXPECT_FALSE(loop.watchdog.feed(busy_since));
  EXPECT_FALSE(loop.watchdog.feedBeforeBracket(capture::CaptureSettings{}, busy_since));
  EXPECT_EQ(loop.pings(), 0u);
}

}  // namespace
}  // namespace glarecam::daemon
