// The linearity calibration finds where a simulated ramp's response bends by one percent, and
// refuses too short a ramp.
#include "calibration/linearity_calibration.h"

#include <gtest/gtest.h>

#include <vector>

#include "calibration/calibration_target_support.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam {
namespace {

using capture::CalibrationTarget;
using capture::CalibrationTargetStack;
using testing::inputFrames;
using testing::kLevels;
using testing::target;

TEST(CalibrateLinearity, FindsWhereTheResponseBendsByOnePercent) {
  const CalibrationTargetStack ramp = target(CalibrationTarget::kLinearity);
  const auto result = calibration::calibrateLinearity(
      inputFrames(ramp), kLevels.black_level_dn,
      calibration::centralRoi(ramp.frames[0].width(), ramp.frames[0].height()), 0.01);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->bend_found);
  // The region's mean is exact to 0.01 DN; the slope, fitted on the 16 points below half the
  // range, to 0.1 %. The crossing (3628 DN) is interpolated linearly between ramp points 120 DN
  // apart, where the deviation curves as c (s - knee)² / s: that interpolation errs by about
  // (120²/8) d'' / d' = 3 DN. 20 DN allows it several times over; a crossing read off the nearest
  // point instead would be up to 60 DN off.
  EXPECT_NEAR(result->slope_dn_per_us, ramp.truth["slope_dn_per_us"].get<double>(), 0.002);
  EXPECT_NEAR(result->saturation_dn, ramp.truth["saturation_dn"].get<double>(), 20);
  EXPECT_LE(result->max_deviation, 0.01);
  EXPECT_LT(result->linear_from_dn, 350);  // the first point above 5 % of the range
}

TEST(CalibrateLinearity, TooShortARampIsAnError) {
  const CalibrationTargetStack ramp = target(CalibrationTarget::kLinearity);
  const auto frames = inputFrames(ramp);
  const auto result = calibration::calibrateLinearity(std::span(frames).first(3), 64,
                                                      calibration::centralRoi(320, 256), 0.01);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("at least 4 different exposures"), std::string::npos);
}

}  // namespace
}  // namespace glarecam
