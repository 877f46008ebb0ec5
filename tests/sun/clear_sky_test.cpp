#include "sun/clear_sky.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"
#include "core/time.h"

namespace glarecam::sun {
namespace {

TEST(ClearSky, AirMassMatchesKastenYoungsTable) {
  // Kasten & Young (1989) Table: 1.000 in the zenith, 2.000 at 30° (secant law still exact to
  // 0.1 %), 5.600 at 10°; their formula gives 37.92 at the horizon (their tabulated 38.09; the
  // formula's stated error is below 0.5 %), so 0.5 % is the tolerance throughout.
  EXPECT_NEAR(relativeAirMass(90), 1.000, 0.005);
  EXPECT_NEAR(relativeAirMass(30), 1.995, 0.01);
  EXPECT_NEAR(relativeAirMass(10), 5.60, 0.028);
  EXPECT_NEAR(relativeAirMass(0), 38.09, 0.19);
}

TEST(ClearSky, HighSunFollowsTheIesFormulaWithTheSecantAirMass) {
  // Above 30° the secant and Kasten–Young air masses differ by at most 0.005 (1.995 against
  // 2.000 at 30°), which changes exp(−0.21 m) by at most 0.21 × 0.005 = 0.105 % of E: the
  // handbook's own formula must come out within 0.15 %.
  for (double elevation : {30.0, 45.0, 60.0, 90.0}) {
    for (int day : {2, 92, 185, 300}) {
      const double expected = 127'500.0 * (1 + 0.034 * std::cos(2 * M_PI * (day - 2) / 365.0)) *
                              std::exp(-0.21 / std::sin(radians(elevation)));
      const auto sky = clearSkyIlluminance(elevation, day);
      ASSERT_TRUE(sky);
      EXPECT_NEAR(sky->illuminance_lx, expected, 1.5e-3 * expected) << elevation << "° day " << day;
      EXPECT_NEAR(sky->illuminance_u_lx, 0.15 * sky->illuminance_lx, 1e-9);
    }
  }
}

TEST(ClearSky, AClearMiddaySunInCentralEuropeIsAboutTheReference) {
  // The default reference (100 klx) is "about a clear midday sun in Central Europe": 60° at the
  // June solstice in Kassel (51.3° N).
  const auto sky = clearSkyIlluminance(62.2, 172);
  ASSERT_TRUE(sky);
  EXPECT_NEAR(sky->illuminance_lx, kDefaultReferenceIlluminanceLx, 5'000);
  // A low sun is much dimmer, and less certain.
  const auto low = clearSkyIlluminance(10, 172);
  ASSERT_TRUE(low);
  EXPECT_LT(low->illuminance_lx, 0.45 * sky->illuminance_lx);
  EXPECT_NEAR(low->illuminance_u_lx / low->illuminance_lx, 0.15, 1e-9);
  const auto horizon = clearSkyIlluminance(0.5, 172);
  ASSERT_TRUE(horizon);
  EXPECT_GT(horizon->illuminance_u_lx / horizon->illuminance_lx, 0.28);
}

TEST(ClearSky, AMountainSiteSeesThinnerAir) {
  const auto sea = clearSkyIlluminance(30, 100, 0);
  const auto peak = clearSkyIlluminance(30, 100, kAirMassScaleHeightM);
  ASSERT_TRUE(sea && peak);
  EXPECT_NEAR(peak->air_mass, sea->air_mass / M_E, 1e-12);
  EXPECT_GT(peak->illuminance_lx, sea->illuminance_lx);
}

TEST(ClearSky, NoSunNoEstimate) {
  EXPECT_FALSE(clearSkyIlluminance(0, 100));
  EXPECT_FALSE(clearSkyIlluminance(-5, 100));
  EXPECT_FALSE(clearSkyIlluminance(std::nan(""), 100));
}

TEST(ClearSky, ASourceForAnInstantAndSite) {
  const SiteLocation kassel{51.3, 9.5, 160};
  auto noon = clearSkySource(*parseIsoTime("2026-06-21T11:20:00Z"), kassel);
  ASSERT_TRUE(noon) << noon.error().message;
  EXPECT_EQ(noon->origin, IlluminanceOrigin::kClearSky);
  EXPECT_GT(noon->illuminance_lx, 95'000);
  EXPECT_LT(noon->illuminance_lx, 110'000);
  ASSERT_TRUE(noon->instrument);
  EXPECT_NE(noon->instrument->find("IES RP-21"), std::string::npos);
  auto night = clearSkySource(*parseIsoTime("2026-06-21T23:00:00Z"), kassel);
  ASSERT_FALSE(night);
  EXPECT_EQ(night.error().code, ErrorCode::kBadInput);
  EXPECT_NE(night.error().message.find("below the horizon"), std::string::npos);
}

// A recorded stack's estimate comes from the sun its rig measured (the geometry block), at sea
// level; a stack without one (a lab lamp) or with the sun down is refused, naming the stack.
TEST(ClearSky, AStacksEstimateIsOfTheSunItsRigMeasured) {
  StackManifest manifest;
  manifest.id = "20260621T113000Z-a40.0";
  EXPECT_EQ(clearSkySourceOfStack(manifest).error().code, ErrorCode::kBadInput);
  EXPECT_NE(clearSkySourceOfStack(manifest).error().message.find(
                "20260621T113000Z-a40.0: its geometry records no sun"),
            std::string::npos);
  manifest.source["geometry"] = {{"source", "fixed"}, {"time", "2026-06-21T11:30:00Z"}};
  EXPECT_FALSE(clearSkySourceOfStack(manifest));
  manifest.source["geometry"] = {
      {"source", "sun"}, {"time", "2026-06-21T11:30:00Z"}, {"sun_elevation_deg", 40.0}};
  const auto estimate = clearSkySourceOfStack(manifest);
  ASSERT_TRUE(estimate) << estimate.error().message;
  const auto sky = clearSkyIlluminance(40.0, 172);  // 21 June is day 172 of 2026
  ASSERT_TRUE(sky);
  EXPECT_DOUBLE_EQ(estimate->illuminance_lx, sky->illuminance_lx);
  EXPECT_DOUBLE_EQ(estimate->illuminance_u_lx, sky->illuminance_u_lx);
  EXPECT_EQ(estimate->origin, IlluminanceOrigin::kClearSky);
  manifest.source["geometry"]["sun_elevation_deg"] = -3.0;
  const auto night = clearSkySourceOfStack(manifest);
  ASSERT_FALSE(night);
  EXPECT_NE(night.error().message.find("below the horizon"), std::string::npos);
  manifest.source["geometry"] = {{"sun_elevation_deg", 40.0}, {"time", "yesterday"}};
  EXPECT_EQ(clearSkySourceOfStack(manifest).error().code, ErrorCode::kBadInput);
}

}  // namespace
}  // namespace glarecam::sun
