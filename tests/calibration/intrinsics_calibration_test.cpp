// The intrinsics calibration recovers the simulated lens from views of a board, does not find a
// wrong board, and warns about poor coverage.
#include "calibration/intrinsics_calibration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "calibration/camera_model.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam {
namespace {

using capture::CalibrationTarget;
using capture::CalibrationTargetOptions;
using capture::CalibrationTargetStack;

std::vector<calibration::BoardView> boardViews(const CalibrationTargetOptions& options) {
  auto stacks = capture::simulateCalibrationTarget(options);
  EXPECT_TRUE(stacks) << stacks.error().message;
  std::vector<calibration::BoardView> views;
  for (const CalibrationTargetStack& stack : *stacks) {
    FloatImage image(stack.frames[0].width(), stack.frames[0].height());
    std::copy(stack.frames[0].data(), stack.frames[0].data() + image.pixelCount(), image.data());
    views.push_back({.name = *stack.manifest.id, .image = std::move(image)});
  }
  return views;
}

// The board target at the size simulate-calibration renders it (9x6 corners need room).
CalibrationTargetOptions boardOptions() {
  CalibrationTargetOptions options;
  options.target = CalibrationTarget::kBoard;
  options.width = 640;
  options.height = 480;
  return options;
}

TEST(CalibrateIntrinsics, RecoversTheSimulatedLens) {
  const CalibrationTargetOptions options = boardOptions();
  const auto views = boardViews(options);
  const auto result =
      calibration::calibrateIntrinsics(views, {.inner_columns = options.board_inner_columns,
                                               .inner_rows = options.board_inner_rows,
                                               .square_mm = options.board_square_mm});
  ASSERT_TRUE(result) << result.error().message;
  const auto truth = capture::simulateCalibrationTarget(options)->front().truth["intrinsics"];
  // Corners of the noisy rendering are located to ~0.11 px RMS (the RMS of the fit at the true
  // model is the same); 12 views of 54 corners then fix the focal length to ~0.1 %: 0.3 %.
  EXPECT_LT(result->rms_reprojection_px, 0.2);
  EXPECT_NEAR(result->intrinsics.fx / truth["fx"].get<double>(), 1.0, 0.003);
  EXPECT_NEAR(result->intrinsics.fy / truth["fy"].get<double>(), 1.0, 0.003);
  // The principal point trades off against the decentering distortion (p1, p2), fitted too: a
  // 0.001 change of p1 moves the best cx by ~2 px at this field of view. 3 px bounds it; a
  // principal point assumed at the centre would be 3.2 px off in x alone.
  EXPECT_NEAR(result->intrinsics.cx, truth["cx"].get<double>(), 3.0);
  EXPECT_NEAR(result->intrinsics.cy, truth["cy"].get<double>(), 3.0);
  EXPECT_NEAR(result->intrinsics.distortion[0], truth["distortion"][0].get<double>(), 0.02);
  EXPECT_NEAR(result->intrinsics.distortion[1], truth["distortion"][1].get<double>(), 0.05);
  // What the glare analysis measures are angles between viewing rays (the ellipse's axes), and
  // there those trade-offs cancel: a shifted principal point with its p1, p2 turns the whole ray
  // bundle by ~0.12°, which no board view can see (the poses absorb it), but leaves the angles
  // between rays. Each pixel's angle from the image centre stays within 0.05° of the truth's
  // (the focal length's 0.1 % at 25° off axis is 0.025°).
  Intrinsics true_model;
  true_model.fx = truth["fx"].get<double>();
  true_model.fy = truth["fy"].get<double>();
  true_model.cx = truth["cx"].get<double>();
  true_model.cy = truth["cy"].get<double>();
  for (int i = 0; i < 5; ++i) true_model.distortion[i] = truth["distortion"][i].get<double>();
  const calibration::CameraModel fitted(result->intrinsics), exact(true_model);
  const calibration::PixelPoint centre{options.width / 2.0, options.height / 2.0};
  double worst_deg = 0;
  for (int y = 0; y <= options.height; y += 40) {
    for (int x = 0; x <= options.width; x += 40) {
      const calibration::PixelPoint p{double(x), double(y)};
      const double fitted_deg = calibration::angleBetweenDeg(fitted.ray(p), fitted.ray(centre));
      const double true_deg = calibration::angleBetweenDeg(exact.ray(p), exact.ray(centre));
      worst_deg = std::max(worst_deg, std::abs(fitted_deg - true_deg));
    }
  }
  EXPECT_LT(worst_deg, 0.05);
  EXPECT_EQ(result->views_used.size(), views.size());
  EXPECT_GE(result->coverage, calibration::kMinCoverage);
}

TEST(CalibrateIntrinsics, AWrongBoardIsNotFoundAndPoorCoverageWarns) {
  const auto views = boardViews(boardOptions());
  const auto wrong = calibration::calibrateIntrinsics(views, {.inner_columns = 8, .inner_rows = 5});
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("found in 0 of 12"), std::string::npos)
      << wrong.error().message;
  // The three central views only (9, 10, 11): the corners of the image see no corner.
  const auto central = calibration::calibrateIntrinsics(
      std::span(views).last(3), {.inner_columns = 9, .inner_rows = 6, .square_mm = 30});
  ASSERT_TRUE(central) << central.error().message;
  EXPECT_LT(central->coverage, calibration::kMinCoverage);
  ASSERT_FALSE(central->warnings.empty());
  EXPECT_NE(central->warnings.front().find("add views with the board in the corners"),
            std::string::npos);
}

}  // namespace
}  // namespace glarecam
