// The auto-bracket's decisions: a frame's levels (hot pixels ignored), the metering steps towards
// a usable peak and background, and plans within the camera's limits.
#include "capture/auto_bracket.h"

#include <gtest/gtest.h>

#include "capture/test_cameras.h"

namespace glarecam::capture {
namespace {

using testing::kSimLimits;
using testing::kSimRangeDn;

TEST(FrameLevels, IgnoreHotPixelsAndFindTheBackgroundPercentile) {
  RawFrame frame(100, 100, 164);  // background 100 DN above a black level of 64
  frame.at(5, 5) = 4095;          // one hot pixel
  for (int y = 40; y < 50; ++y) {
    for (int x = 40; x < 50; ++x) frame.at(x, y) = 2064;  // a 100-pixel peak at 2000 DN
  }
  FrameLevels levels = measureFrameLevels(frame, 64, 4000);
  EXPECT_DOUBLE_EQ(levels.peak_dn, 2000);
  EXPECT_DOUBLE_EQ(levels.background_dn, 100);
  EXPECT_FALSE(levels.peak_clipped);
  for (int x = 0; x < 100; ++x) frame.at(x, 60) = 4095;
  levels = measureFrameLevels(frame, 64, 4000);
  EXPECT_TRUE(levels.peak_clipped);
}

TEST(AutoBracket, MeteringShortensClippedPeaksAndLengthensDarkOnes) {
  const AutoBracketOptions options;
  // Clipped: a decade shorter.
  auto next = nextPeakMetering({1000, {kSimRangeDn, 10, true}}, kSimRangeDn, kSimLimits, options);
  ASSERT_TRUE(next);
  EXPECT_DOUBLE_EQ(*next, 100);
  // Dark (1 % of range): towards 70 % of range, at most 100× at once.
  next = nextPeakMetering({1000, {39.36, 1, false}}, kSimRangeDn, kSimLimits, options);
  ASSERT_TRUE(next);
  EXPECT_NEAR(*next, 70000, 1);
  // Usable.
  EXPECT_FALSE(nextPeakMetering({1000, {2000, 1, false}}, kSimRangeDn, kSimLimits, options));
  // At the camera's limit nothing better exists.
  EXPECT_FALSE(nextPeakMetering({10, {kSimRangeDn, 10, true}}, kSimRangeDn, kSimLimits, options));
  EXPECT_FALSE(nextPeakMetering({2e6, {1, 0, false}}, kSimRangeDn, kSimLimits, options));
  // The background below 2 % of the range is metered longer, towards 50 % of the range.
  next = nextBackgroundMetering({1000, {2000, 0, false}}, kSimRangeDn, kSimLimits, options);
  ASSERT_TRUE(next);
  EXPECT_DOUBLE_EQ(*next, 100000);
  EXPECT_FALSE(
      nextBackgroundMetering({1000, {2000, 100, false}}, kSimRangeDn, kSimLimits, options));
}

TEST(AutoBracket, PlansWithinTheCameraLimits) {
  CameraLimits narrow = kSimLimits;
  narrow.min_exposure_us = 50;
  narrow.max_exposure_us = 20000;
  auto plan = planForRates(10.0, 1e-4, kSimRangeDn, narrow, {});
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_GE(plan->exposures_us.front(), 50);
  EXPECT_LE(plan->exposures_us.back(), 20000);
  EXPECT_TRUE(plan->background_underexposed);
  EXPECT_NEAR(clippedPeakRate(100, kSimRangeDn), 10 * kSimRangeDn / 100, 1e-9);
}

}  // namespace
}  // namespace glarecam::capture
