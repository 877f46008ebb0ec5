#include "hazard/criteria.h"

#include <gtest/gtest.h>

namespace glarecam::hazard {
namespace {

const Criterion& criterion(const std::string& id) {
  for (const Criterion& c : knownCriteria())
    if (c.id == id) return c;
  throw std::runtime_error("no criterion " + id);
}

TEST(HazardCriteria, LaiIsThirtyMinutesADayOrThirtyHoursAYear) {
  const Criterion& lai = criterion("lai");
  EXPECT_FALSE(assess(lai, 30, 0).exceeded);  // exactly 30 minutes: not more than 30
  EXPECT_TRUE(assess(lai, 31, 0).exceeded);
  EXPECT_TRUE(assess(lai, 31, 0).day_exceeded);
  EXPECT_FALSE(assess(lai, 10, 1800 / 60.0).exceeded);  // 1800 minutes = 30 h
  EXPECT_TRUE(assess(lai, 10, 1801 / 60.0).exceeded);
  EXPECT_TRUE(assess(lai, 10, 1801 / 60.0).year_exceeded);
  EXPECT_EQ(assess(lai, 31, 0).text, "significant");
  EXPECT_EQ(assess(lai, 30, 30).text, "not significant");
}

TEST(HazardCriteria, SwissPracticeIsThirtyMinutesADayAndFiftyHoursAYear) {
  const Criterion& ch = criterion("ch");
  EXPECT_FALSE(assess(ch, 30, 50).exceeded);
  EXPECT_TRUE(assess(ch, 31, 10).exceeded);
  EXPECT_FALSE(assess(ch, 30, 3000 / 60.0).exceeded);
  EXPECT_TRUE(assess(ch, 30, 3001 / 60.0).exceeded);
  EXPECT_EQ(assess(ch, 30, 3001 / 60.0).text, "not tolerable");
  EXPECT_EQ(assess(ch, 30, 40).text, "tolerable");
  const nlohmann::json json = criterionJson(ch);
  EXPECT_EQ(json["max_minutes_per_day"], 30);
  EXPECT_EQ(json["max_hours_per_year"], 50);
}

TEST(HazardCriteria, ParsesAListAndRefusesUnknownOrRepeatedOnes) {
  const auto both = parseCriteria("lai,ch", "--criteria");
  ASSERT_TRUE(both);
  ASSERT_EQ(both->size(), 2u);
  EXPECT_EQ((*both)[1].id, "ch");
  EXPECT_EQ(parseCriteria(" ch ", "--criteria")->front().id, "ch");
  const auto unknown = parseCriteria("lia", "--criteria");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(unknown.error().message, "--criteria: unknown criterion \"lia\" (did you mean lai?)");
  EXPECT_FALSE(parseCriteria("lai,lai", "--criteria"));
  EXPECT_FALSE(parseCriteria("", "--criteria"));
}

}  // namespace
}  // namespace glarecam::hazard
