// The dark calibration recovers a simulated dark target's black level and exactly its hot
// pixels, and refuses too few frames or a lit one.
#include "calibration/dark_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
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
  // The median of 82k per-pixel means (each of 32 frames: σ = √(0.5² + 2²/32) = 0.61 DN) has a
  // standard error of 0.003 DN; 0.05 DN allows the integer rounding of the raw values.
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
  // Temporal noise: read noise and quantisation, √(2² + 1/12) = 2.02 DN, from 31 pair
  // differences over 82k pixels each (0.1 % standard error): 2 % covers it.
  ASSERT_EQ(result->levels.size(), 2u);
  for (const auto& level : result->levels) {
    ASSERT_TRUE(level.temporal_noise_dn);
    EXPECT_NEAR(*level.temporal_noise_dn, std::sqrt(4.0 + 1.0 / 12), 0.04);
  }
}

// The dark frame removes the fixed pattern (0.5 DN) and adds its own noise (2.02 DN over the
// square root of its frames): with 32 frames (0.36 DN) subtracting it pays, with 4 (1.01 DN) it
// does not, and calibrate dark says so with the frames it takes (about (2.02 / 0.5)² = 17).
TEST(CalibrateDark, WarnsWhenTheDarkFramesOwnNoiseExceedsTheFixedPattern) {
  const CalibrationTargetStack dark = target(CalibrationTarget::kDark);
  const auto frames = inputFrames(dark);
  const auto all = calibration::calibrateDark(frames);
  ASSERT_TRUE(all) << all.error().message;
  // The pattern's estimate: the dark frame's spread less its noise, over 82k pixels: 5 %.
  EXPECT_NEAR(all->fixed_pattern_dn, dark.truth["fixed_pattern_dn"].get<double>(), 0.025);
  EXPECT_NEAR(all->dark_frame_noise_dn, std::sqrt(4.0 + 1.0 / 12) / std::sqrt(32.0), 0.01);
  EXPECT_FALSE(calibration::darkFrameNoiseWarning(*all));

  const std::size_t per_exposure = frames.size() / 2;
  std::vector<calibration::InputFrame> few(frames.begin(), frames.begin() + 4);
  few.insert(few.end(), frames.begin() + static_cast<std::ptrdiff_t>(per_exposure),
             frames.begin() + static_cast<std::ptrdiff_t>(per_exposure) + 4);
  const auto four = calibration::calibrateDark(few);
  ASSERT_TRUE(four) << four.error().message;
  EXPECT_NEAR(four->fixed_pattern_dn, 0.5, 0.05);
  const auto warning = calibration::darkFrameNoiseWarning(*four);
  ASSERT_TRUE(warning);
  EXPECT_NE(warning->find("exceeds the fixed pattern"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("or more frames at the longest exposure"), std::string::npos) << *warning;
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
