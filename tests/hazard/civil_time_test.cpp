#include "hazard/civil_time.h"

#include <gtest/gtest.h>

#include <chrono>

namespace glarecam::hazard {
namespace {

UtcTime utcAt(int y, unsigned m, unsigned d, int hour, int minute = 0) {
  return std::chrono::time_point_cast<std::chrono::microseconds>(
             std::chrono::sys_days{std::chrono::year{y} / m / d}) +
         std::chrono::hours(hour) + std::chrono::minutes(minute);
}

TEST(CivilTime, TheEuropeanUnionsRule) {
  // 2027: summer time from 28 March 01:00 UTC to 31 October 01:00 UTC (the last Sundays).
  EXPECT_FALSE(inDaylightSaving(DaylightSaving::kEu, utcAt(2027, 3, 28, 0, 59), 1));
  EXPECT_TRUE(inDaylightSaving(DaylightSaving::kEu, utcAt(2027, 3, 28, 1, 0), 1));
  EXPECT_TRUE(inDaylightSaving(DaylightSaving::kEu, utcAt(2027, 10, 31, 0, 59), 1));
  EXPECT_FALSE(inDaylightSaving(DaylightSaving::kEu, utcAt(2027, 10, 31, 1, 0), 1));
  EXPECT_EQ(civilOffsetH(DaylightSaving::kEu, utcAt(2027, 7, 1, 12), 1), 2);
  EXPECT_EQ(civilOffsetH(DaylightSaving::kEu, utcAt(2027, 1, 1, 12), 1), 1);
  // The same instant everywhere in the EU: Lisbon (UTC+0) too.
  EXPECT_TRUE(inDaylightSaving(DaylightSaving::kEu, utcAt(2027, 3, 28, 1, 0), 0));
}

TEST(CivilTime, TheUnitedStatesRule) {
  // 2027 in New York (UTC−5): from 14 March 02:00 EST (07:00 UTC) to 7 November 02:00 EDT
  // (06:00 UTC).
  EXPECT_FALSE(inDaylightSaving(DaylightSaving::kUs, utcAt(2027, 3, 14, 6, 59), -5));
  EXPECT_TRUE(inDaylightSaving(DaylightSaving::kUs, utcAt(2027, 3, 14, 7, 0), -5));
  EXPECT_TRUE(inDaylightSaving(DaylightSaving::kUs, utcAt(2027, 11, 7, 5, 59), -5));
  EXPECT_FALSE(inDaylightSaving(DaylightSaving::kUs, utcAt(2027, 11, 7, 6, 0), -5));
}

TEST(CivilTime, NoneAndTheOption) {
  EXPECT_FALSE(inDaylightSaving(DaylightSaving::kNone, utcAt(2027, 7, 1, 12), 1));
  EXPECT_EQ(*parseDaylightSaving("eu", "--daylight-saving"), DaylightSaving::kEu);
  const Result<DaylightSaving> bad = parseDaylightSaving("summer", "--daylight-saving");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kBadInput);
  EXPECT_NE(bad.error().message.find("--daylight-saving \"summer\""), std::string::npos);
}

}  // namespace
}  // namespace glarecam::hazard
