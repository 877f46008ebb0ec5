#include "capture/bracketing.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glarecam::capture {
namespace {

constexpr double kRange = 3936.0;  // 4000 saturation - 64 black

TEST(Bracketing, CoversPeakToBackgroundInDecadeSteps) {
  // Peak 40 DN/µs, background 0.002 DN/µs: four decades and a bit.
  auto plan = planBracket(40.0, 0.002, kRange);
  ASSERT_TRUE(plan) << plan.error().message;
  const auto& t = plan->exposures_us;
  ASSERT_GE(t.size(), 6u);
  EXPECT_NEAR(t.front(), 0.7 * kRange / 40.0, 1.0);  // peak at 70 % of the range
  EXPECT_NEAR(t.back(), 0.5 * kRange / 0.002, 1.0);  // background at 50 %
  for (std::size_t i = 1; i < t.size(); ++i) {
    EXPECT_GT(t[i], t[i - 1]);
    EXPECT_LE(t[i] / t[i - 1], 10.0 * 1.001);  // at most a decade apart
  }
  EXPECT_FALSE(plan->peak_clipped);
  EXPECT_FALSE(plan->background_underexposed);
}

TEST(Bracketing, AddsFramesWhenSixAreNotEnough) {
  BracketOptions options;
  options.min_exposure_us = 1.0;
  options.max_exposure_us = 1.0e9;
  auto plan = planBracket(100.0, 1e-5, kRange, options);  // about 6.9 decades
  ASSERT_TRUE(plan);
  EXPECT_FALSE(plan->peak_clipped);
  EXPECT_GE(plan->exposures_us.size(), 8u);
}

TEST(Bracketing, RespectsTheCamerasLimitsAndSaysSo) {
  BracketOptions options;
  options.min_exposure_us = 20;
  options.max_exposure_us = 1000;
  auto plan = planBracket(1000.0, 0.01, kRange, options);
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->exposures_us.front(), 20.0);
  EXPECT_EQ(plan->exposures_us.back(), 1000.0);
  EXPECT_TRUE(plan->peak_clipped);
  EXPECT_TRUE(plan->background_underexposed);
}

TEST(Bracketing, RoundsToTheCamerasResolution) {
  BracketOptions options;
  options.exposure_step_us = 10;
  auto plan = planBracket(3.0, 0.01, kRange, options);
  ASSERT_TRUE(plan);
  for (double t : plan->exposures_us) EXPECT_EQ(std::fmod(t, 10.0), 0.0) << t;
}

TEST(Bracketing, RefusesNonsense) {
  EXPECT_FALSE(planBracket(0.0, 1.0, kRange));
  EXPECT_FALSE(planBracket(1.0, -1.0, kRange));
  EXPECT_FALSE(planBracket(std::nan(""), 1.0, kRange));
  BracketOptions options;
  options.min_frames = 0;
  EXPECT_FALSE(planBracket(1.0, 0.1, kRange, options));
}

}  // namespace
}  // namespace glarecam::capture
