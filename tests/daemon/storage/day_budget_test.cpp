// The settings check of max_use_gib: a day's stacks as the schedule takes them, against the sun
// of a known site and day, and the warning when the budget cannot hold them.
#include "daemon/storage/day_budget.h"

#include <gtest/gtest.h>

#include "daemon/output_test_support.h"
#include "daemon/storage/disk_space.h"

namespace glarecam::daemon {
namespace {

// The simulated rig's site (48° N, 7.85° E) on the June solstice, from its mean solar midnight.
const sun::SiteLocation kSite{.latitude_deg = 48.0, .longitude_deg = 7.85, .altitude_m = 278};
const sun::ModuleOrientation kSouth{.tilt_deg = 24.5, .azimuth_deg = 180};
const UtcTime kMidnight = *parseIsoTime("2026-06-21T00:00:00Z") - std::chrono::seconds(1884);

double hoursOf(const DayEstimate& day, std::chrono::seconds interval) {
  return (day.stacks - 1) * std::chrono::duration<double>(interval).count() / 3600;  // gaps
}

// At 48° N on the solstice the sun is up for 16.2 h (declination 23.44°: cos H = −tan φ tan δ
// gives 15.8 h for the centre at the horizon; refraction and the disc's radius add about 0.3 h),
// so an interval of 10 minutes takes 16.2 × 6 stacks (and one: slots, not gaps), to one stack
// (the 5-minute sampling).
TEST(DayBudget, AnIntervalTakesTheDaysSunHoursOverTheInterval) {
  ScheduleConfig schedule;  // an interval of 600 s by default
  ASSERT_EQ(schedule.mode, ScheduleMode::kInterval);
  ASSERT_EQ(schedule.interval, std::chrono::seconds(600));
  const auto day = estimateDayStacks(schedule, kSite, std::nullopt, kMidnight, 1.0);
  ASSERT_TRUE(day);
  EXPECT_NEAR(hoursOf(*day, schedule.interval), 16.2, 0.2) << day->basis;
  EXPECT_NE(day->basis.find("every 600 s over 16."), std::string::npos) << day->basis;
  // With the module known, only while α is below 80°: the south-facing module sees the sun for
  // fewer hours (the early morning and late evening sun is behind it or grazing).
  const auto facing = estimateDayStacks(schedule, kSite, kSouth, kMidnight, 1.0);
  ASSERT_TRUE(facing);
  EXPECT_LT(facing->stacks, day->stacks - 12);
  EXPECT_GT(facing->stacks, 60);
  EXPECT_NE(facing->basis.find("sun on the module"), std::string::npos);
  // A time lapse of 3600× turns a 2 s interval into two hours of the simulated sun.
  ScheduleConfig fast;
  fast.interval = std::chrono::seconds(2);
  const auto lapsed = estimateDayStacks(fast, kSite, std::nullopt, kMidnight, 3600.0);
  ASSERT_TRUE(lapsed);
  EXPECT_EQ(lapsed->stacks, 9);  // 16.2 h / 2 h: 8 gaps, 9 slots
}

TEST(DayBudget, AlphaTargetsAreCrossedMorningAndAfternoon) {
  ScheduleConfig schedule{.mode = ScheduleMode::kAlphaTargets,
                          .alpha_targets_deg = defaultAlphaTargetsDeg()};
  const auto guessed = estimateDayStacks(schedule, kSite, std::nullopt, kMidnight, 1.0);
  ASSERT_TRUE(guessed);
  EXPECT_EQ(guessed->stacks, 32);
  // The simulated module faces the noon sun squarely: α falls through every target in the
  // morning and rises through them in the afternoon (simulated_rig.h).
  const auto crossed = estimateDayStacks(schedule, kSite, kSouth, kMidnight, 1.0);
  ASSERT_TRUE(crossed);
  EXPECT_EQ(crossed->stacks, 32) << crossed->basis;
  schedule.mode = ScheduleMode::kButton;
  EXPECT_FALSE(estimateDayStacks(schedule, kSite, kSouth, kMidnight, 1.0));
  schedule.mode = ScheduleMode::kInterval;
  EXPECT_FALSE(estimateDayStacks(schedule, std::nullopt, kSouth, kMidnight, 1.0));
}

TEST(DayBudget, WarnsWhenTheBudgetHoldsFewerStacksThanADay) {
  const DayEstimate day{.stacks = 36, .basis = "every 1200 s over 12.0 h of sun"};
  const auto warning = dayBudgetWarning(200ull << 20, day, 9ull << 20);
  ASSERT_TRUE(warning);
  EXPECT_EQ(*warning,
            "max_use_gib (200.0 MiB) holds about 22 stacks with their results (9.0 MiB each), "
            "fewer than the 36 a day the schedule takes (every 1200 s over 12.0 h of sun): capture "
            "will pause every day once the budget is full; raise max_use_gib, or capture less "
            "often");
  EXPECT_FALSE(dayBudgetWarning(400ull << 20, day, 9ull << 20));
  EXPECT_FALSE(dayBudgetWarning(200ull << 20, day, 0));
}

TEST(DayBudget, TheNewestStackWithItsResultIsMeasured) {
  testing::TempDir dir;
  const OutputTree tree(dir / "out");
  ASSERT_TRUE(tree.prepare());
  EXPECT_FALSE(newestStackBytes(tree));
  testing::makeProcessed(tree, "20260621T080000Z-a40.00", 5000);
  testing::makeGlarecamStack(tree.stacks() / "20260621T090000Z-a30.00", 7000);  // unprocessed
  testing::makeGlarecamStack(tree.stacks() / "zz-notes", 1);                    // not a stack id
  // The newest processed one: the unprocessed one's result is not there yet.
  const std::uint64_t first_json = std::filesystem::file_size(
      tree.results() / "20260621T080000Z-a40.00" / pipeline::kResultFileName);
  EXPECT_EQ(newestStackBytes(tree), 5000u + 30u + 3 * 500u + first_json);
  testing::makeGlarecamResult(tree.results() / "20260621T090000Z-a30.00", 1000, 30.0, 100);
  const std::uint64_t json_bytes = std::filesystem::file_size(
      tree.results() / "20260621T090000Z-a30.00" / pipeline::kResultFileName);
  EXPECT_EQ(newestStackBytes(tree), 7000u + 30u + 300u + json_bytes);
}

}  // namespace
}  // namespace glarecam::daemon
