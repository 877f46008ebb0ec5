// The day a stack belongs to: the site's mean solar day.
#include "daemon/day_products.h"

#include <gtest/gtest.h>

#include <optional>

namespace glarecam::daemon {
namespace {

TEST(DayProducts, TheDayIsTheSitesMeanSolarDay) {
  EXPECT_EQ(stackDay("20260621T101503Z-a42.30", std::nullopt), "2026-06-21");
  EXPECT_EQ(stackDay("20260621T231503Z", 7.85), "2026-06-21");    // 23:46 local mean time
  EXPECT_EQ(stackDay("20260621T234503Z", 7.85), "2026-06-22");    // 00:16
  EXPECT_EQ(stackDay("20260622T010000Z", -105.0), "2026-06-21");  // Colorado: 18:00 the day before
  EXPECT_FALSE(stackDay("alpha-40", std::nullopt));
  EXPECT_FALSE(stackDay("20261341T101503Z", std::nullopt));
}

}  // namespace
}  // namespace glarecam::daemon
