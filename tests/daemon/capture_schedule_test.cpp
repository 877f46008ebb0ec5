// When glarecamd takes its next scheduled stack, on the manual clock: the interval's grid (missed
// slots not caught up), button mode, the α targets planned from the module and the site with the
// repeat guard, and a wall clock that jumped.
#include "daemon/capture_schedule.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "daemon/alpha_schedule.h"
#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::ManualClock;
using testing::utc;

ScheduleConfig every(std::chrono::seconds interval) {
  ScheduleConfig config;
  config.mode = ScheduleMode::kInterval;
  config.interval = interval;
  return config;
}

ScheduleConfig onTheButton() {
  ScheduleConfig config;
  config.mode = ScheduleMode::kButton;
  return config;
}

ScheduleConfig alphaTargets(std::vector<double> targets) {
  ScheduleConfig config;
  config.mode = ScheduleMode::kAlphaTargets;
  config.alpha_targets_deg = std::move(targets);
  return config;
}

// The simulated rig's site and module (simulated_rig.h): α falls through 80° … 5° each morning.
const CaptureSchedule::Geometry kRig{
    .site = sun::SiteLocation{.latitude_deg = 48, .longitude_deg = 7.85, .altitude_m = 278},
    .module = sun::ModuleOrientation{.tilt_deg = 24.5, .azimuth_deg = 180}};

TEST(CaptureSchedule, DescribesItsMode) {
  EXPECT_EQ(CaptureSchedule(every(600s)).describe(), "every 600 s");
  EXPECT_EQ(CaptureSchedule(alphaTargets({20, 40, 60})).describe(), "at 3 α targets");
  EXPECT_EQ(CaptureSchedule(onTheButton()).describe(), "on the button and SIGUSR1");
}

TEST(CaptureSchedule, TheIntervalStartsAtOnceAndKeepsItsGrid) {
  ManualClock clock(utc("2026-06-21T08:00:00Z"));
  const SteadyTime start = clock.now();
  CaptureSchedule schedule(every(600s));
  schedule.plan(clock, std::nullopt, {});
  ASSERT_EQ(schedule.next(), start);
  EXPECT_TRUE(schedule.due(clock.now()));
  EXPECT_EQ(schedule.nextWallTime(clock), utc("2026-06-21T08:00:00Z"));
  clock.advance(42s);  // the bracket took a while: the grid does not move
  schedule.plan(clock, clock.utcNow(), {});
  EXPECT_EQ(schedule.next(), start + 600s);
  EXPECT_FALSE(schedule.due(clock.now()));
  EXPECT_EQ(schedule.nextWallTime(clock), utc("2026-06-21T08:10:00Z"));
  EXPECT_FALSE(schedule.nextTargetDeg());
}

TEST(CaptureSchedule, MissedSlotsAreNotCaughtUp) {
  ManualClock clock(utc("2026-06-21T08:00:00Z"));
  const SteadyTime start = clock.now();
  CaptureSchedule schedule(every(600s));
  schedule.plan(clock, std::nullopt, {});
  clock.advance(2000s);  // the slots at 600, 1200 and 1800 s passed (the disk was full)
  schedule.plan(clock, clock.utcNow(), {});
  EXPECT_EQ(schedule.next(), start + 2600s);
}

TEST(CaptureSchedule, APlanMadeAgainNeverWaitsLongerThanTheNewInterval) {
  ManualClock clock(utc("2026-06-21T08:00:00Z"));
  const SteadyTime start = clock.now();
  CaptureSchedule schedule(every(600s));
  schedule.plan(clock, std::nullopt, {});
  schedule.plan(clock, clock.utcNow(), {});  // next at 600 s
  clock.advance(100s);
  schedule.reconfigure(every(60s));  // a reload
  schedule.plan(clock, std::nullopt, {});
  EXPECT_EQ(schedule.next(), start + 160s);
  schedule.reconfigure(every(600s));
  schedule.plan(clock, std::nullopt, {});  // the nearer slot stays
  EXPECT_EQ(schedule.next(), start + 160s);
}

TEST(CaptureSchedule, TheButtonModePlansNoSlot) {
  ManualClock clock(utc("2026-06-21T08:00:00Z"));
  CaptureSchedule schedule(onTheButton());
  schedule.plan(clock, std::nullopt, kRig);
  EXPECT_FALSE(schedule.next());
  EXPECT_FALSE(schedule.due(clock.now() + 24h));
  EXPECT_FALSE(schedule.nextWallTime(clock));
  EXPECT_FALSE(schedule.replanAt());
}

TEST(CaptureSchedule, AlphaTargetsWaitForTheModuleAndTryAgainLater) {
  ManualClock clock(utc("2026-06-21T05:00:00Z"));
  CaptureSchedule schedule(alphaTargets({80, 60}));
  schedule.plan(clock, std::nullopt, {.site = kRig.site, .module = std::nullopt});
  EXPECT_FALSE(schedule.next());
  EXPECT_EQ(schedule.replanAt(), clock.now() + kReplanDelay);
  EXPECT_EQ(schedule.unplannedReason(), "α targets need the module's tilt");
}

TEST(CaptureSchedule, AlphaTargetsPlanTheNextCrossing) {
  ManualClock clock(utc("2026-06-21T05:00:00Z"));
  CaptureSchedule schedule(alphaTargets({80, 60}));
  schedule.plan(clock, std::nullopt, kRig);
  const auto crossings = alphaCrossings(*kRig.site, *kRig.module, clock.utcNow(), kAlphaPlanHorizon,
                                        std::vector<double>{80, 60});
  ASSERT_TRUE(crossings) << crossings.error().message;
  ASSERT_FALSE(crossings->empty());
  EXPECT_EQ(schedule.nextTargetDeg(), 80.0);  // the morning's first
  EXPECT_EQ(schedule.next(), clock.steadyAt(crossings->front().time));
  EXPECT_FALSE(schedule.replanAt());
  EXPECT_TRUE(schedule.unplannedReason().empty());
}

TEST(CaptureSchedule, ATargetJustTakenIsNotTakenAgainWithinTheRepeatGuard) {
  ManualClock clock(utc("2026-06-21T05:00:00Z"));
  CaptureSchedule schedule(alphaTargets({80, 60}));
  schedule.plan(clock, std::nullopt, kRig);
  ASSERT_TRUE(schedule.next());
  clock.advance(*schedule.next() - clock.now());  // at the 80° crossing
  // Planned again at the crossing without taking it, the same target comes first ...
  schedule.plan(clock, std::nullopt, kRig);
  EXPECT_EQ(schedule.nextTargetDeg(), 80.0);
  // ... once taken, the guard skips it: the next is 60°.
  schedule.take(clock.utcNow());
  schedule.plan(clock, clock.utcNow(), kRig);
  EXPECT_EQ(schedule.nextTargetDeg(), 60.0);
}

// A loaded machine: the 80° stack's bracket lasted until after the sun crossed 75°. The 75° stack
// is still owed (due at once), not skipped for the 70° one.
TEST(CaptureSchedule, ATargetCrossedDuringTheLastStackIsStillOwed) {
  ManualClock clock(utc("2026-06-21T05:00:00Z"));
  CaptureSchedule schedule(alphaTargets({80, 75, 70}));
  schedule.plan(clock, std::nullopt, kRig);
  ASSERT_EQ(schedule.nextTargetDeg(), 80.0);
  clock.advance(*schedule.next() - clock.now());  // the 80° stack begins
  const UtcTime begun = clock.utcNow();
  const auto crossings = alphaCrossings(*kRig.site, *kRig.module, begun, kAlphaPlanHorizon,
                                        std::vector<double>{75, 70});
  ASSERT_TRUE(crossings) << crossings.error().message;
  ASSERT_GE(crossings->size(), 2u);
  ASSERT_EQ(crossings->at(0).target_deg, 75.0);
  ASSERT_EQ(crossings->at(1).target_deg, 70.0);
  // It ends halfway between the 75° and the 70° crossings.
  clock.advance((crossings->at(0).time - begun) +
                (crossings->at(1).time - crossings->at(0).time) / 2);
  schedule.take(begun);
  schedule.plan(clock, begun, kRig);
  EXPECT_EQ(schedule.nextTargetDeg(), 75.0);
  EXPECT_TRUE(schedule.due(clock.now()));
}

TEST(CaptureSchedule, NoCrossingWithinTheHorizonIsSaid) {
  ManualClock clock(utc("2026-12-21T00:00:00Z"));
  CaptureSchedule schedule(alphaTargets({5}));
  // A north-facing wall at 48° N: the sun never shines on it at α 5°.
  schedule.plan(
      clock, std::nullopt,
      {.site = kRig.site, .module = sun::ModuleOrientation{.tilt_deg = 90, .azimuth_deg = 0}});
  EXPECT_FALSE(schedule.next());
  EXPECT_EQ(schedule.unplannedReason(), "no α target is crossed in the next 24 h");
  EXPECT_EQ(schedule.replanAt(), clock.now() + kReplanDelay);
}

TEST(CaptureSchedule, AWallClockThatJumpedIsSeen) {
  ManualClock clock(utc("2026-06-21T05:00:00Z"));
  CaptureSchedule schedule(alphaTargets({80, 60}));
  schedule.plan(clock, std::nullopt, kRig);
  EXPECT_FALSE(schedule.wallClockJump(clock));
  // A few seconds of drift correction are no jump ...
  clock.setUtcStart(utc("2026-06-21T05:00:02Z"));
  EXPECT_FALSE(schedule.wallClockJump(clock));
  // ... NTP's first synchronisation an hour ahead is.
  clock.setUtcStart(utc("2026-06-21T06:00:00Z"));
  EXPECT_EQ(schedule.wallClockJump(clock), std::chrono::nanoseconds(1h));
  // An interval plan does not depend on the wall clock.
  CaptureSchedule interval(every(600s));
  interval.plan(clock, std::nullopt, {});
  clock.setUtcStart(utc("2026-06-21T09:00:00Z"));
  EXPECT_FALSE(interval.wallClockJump(clock));
}

}  // namespace
}  // namespace glarecam::daemon
