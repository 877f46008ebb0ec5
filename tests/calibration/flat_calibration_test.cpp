// The flat calibration recovers a simulated flat target's vignetting, normalised at the principal
// point, and refuses a saturated or dark frame.
#include "calibration/flat_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "calibration/calibration_target_support.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam {
namespace {

using capture::CalibrationTarget;
using capture::CalibrationTargetOptions;
using capture::CalibrationTargetStack;
using testing::inputFrames;
using testing::kLevels;
using testing::target;

TEST(CalibrateFlat, RecoversTheVignettingNormalisedAtThePrincipalPoint) {
  const CalibrationTargetOptions options;
  const CalibrationTargetStack flat = target(CalibrationTarget::kFlat);
  const double cx = (options.width - 1) / 2.0, cy = (options.height - 1) / 2.0;
  const auto result = calibration::calibrateFlat(inputFrames(flat), kLevels, cx, cy);
  ASSERT_TRUE(result) << result.error().message;
  const FloatImage truth =
      capture::naturalVignetting(options.width, options.height, options.horizontal_fov_deg);
  // Per pixel the 8-frame mean has 0.56 % shot noise at 2000 DN; over 16x16 blocks that is
  // 0.035 %, and the normalisation window adds 0.05 %. 0.5 % is ten times both, and fails on any
  // systematic error (a black level left in is 3 %, the corners' vignetting 30 %).
  constexpr int kBlock = 16;
  for (int by = 0; by + kBlock <= options.height; by += kBlock) {
    for (int bx = 0; bx + kBlock <= options.width; bx += kBlock) {
      double measured = 0, expected = 0;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) {
          measured += result->flat_field.at(x, y);
          expected += truth.at(x, y);
        }
      ASSERT_NEAR(measured / expected, 1.0, 0.005) << "block at " << bx << "," << by;
    }
  }
  EXPECT_LT(result->min_value, 0.8);  // the corners' cos⁴ at 40° across
}

TEST(CalibrateFlat, ASaturatedOrDarkFrameIsAnError) {
  const CalibrationTargetStack ramp = target(CalibrationTarget::kLinearity);
  const auto frames = inputFrames(ramp);
  const std::size_t last = ramp.frames.size() - 1;
  const auto saturated =
      calibration::calibrateFlat(std::span(frames).subspan(last), kLevels, 100, 100);
  ASSERT_FALSE(saturated);
  EXPECT_NE(saturated.error().message.find("must not saturate"), std::string::npos);
  const auto dark = calibration::calibrateFlat(std::span(frames).first(1), kLevels, 100, 100);
  ASSERT_FALSE(dark);
  EXPECT_NE(dark.error().message.find("too dark for a flat"), std::string::npos);
}

}  // namespace
}  // namespace glarecam
