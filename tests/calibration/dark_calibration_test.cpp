// The dark calibration recovers a simulated dark target's black level and exactly its hot
// pixels, and refuses too few frames or a lit one.
#include "calibration/dark_calibration.h"

#include <gtest/gtest.h>

#include <set>
#include <span>
#include <vector>

#include "calibration/calibration_target_support.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam {
namespace {

using capture::CalibrationTarget;
using capture::CalibrationTargetStack;
using testing::inputFrames;
using testing::target;

TEST(CalibrateDark, RecoversTheBlackLevelAndExactlyTheHotPixels) {
  const CalibrationTargetStack dark = target(CalibrationTarget::kDark);
  const auto result = calibration::calibrateDark(inputFrames(dark));
  ASSERT_TRUE(result) << result.error().message;
  // The median of 82k per-pixel means (each of 4 frames: σ = √(0.5² + 2²/4) = 1.1 DN) has a
  // standard error of 0.005 DN; 0.05 DN allows the integer rounding of the raw values.
  EXPECT_NEAR(result->black_level_dn, dark.truth["black_level_dn"].get<double>(), 0.05);
  // Hot pixels gain >= 200 DN in 10 ms against a threshold ~10 DN above the median, and a normal
  // pixel passes 6σ once in 5e8: the sets must be equal.
  std::set<std::pair<int, int>> found, truth;
  for (int y = 0; y < result->hot_pixels.height(); ++y)
    for (int x = 0; x < result->hot_pixels.width(); ++x)
      if (result->hot_pixels.at(x, y)) found.insert({x, y});
  for (const auto& p : dark.truth["hot_pixels"]) truth.insert({p[0].get<int>(), p[1].get<int>()});
  EXPECT_EQ(found, truth);
  EXPECT_EQ(result->hot_pixel_count, truth.size());
  // Temporal noise: read noise and quantisation, √(2² + 1/12) = 2.02 DN, from 3 pair
  // differences over 82k pixels each (0.3 % standard error): 2 % covers it.
  ASSERT_EQ(result->levels.size(), 2u);
  for (const auto& level : result->levels) {
    ASSERT_TRUE(level.temporal_noise_dn);
    EXPECT_NEAR(*level.temporal_noise_dn, std::sqrt(4.0 + 1.0 / 12), 0.04);
  }
}

TEST(CalibrateDark, TooFewFramesAndALitFrameAreErrors) {
  const CalibrationTargetStack dark = target(CalibrationTarget::kDark);
  const auto frames = inputFrames(dark);
  const auto one = calibration::calibrateDark(std::span(frames).first(1));
  ASSERT_FALSE(one);
  EXPECT_NE(one.error().message.find("needs at least 2 dark frames"), std::string::npos);

  CalibrationTargetStack lit = dark;
  lit.frames[3] = target(CalibrationTarget::kFlat).frames[0];
  const auto refused = calibration::calibrateDark(inputFrames(lit));
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("target/frame-03.png: not a dark frame"),
            std::string::npos)
      << refused.error().message;
}

}  // namespace
}  // namespace glarecam
