// Each calibration procedure recovers the known truth of a simulated calibration target
// (capture/sim/calibration_targets.h), and refuses bad inputs with a clear message.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "calibration/camera_model.h"
#include "calibration/dark_calibration.h"
#include "calibration/flat_calibration.h"
#include "calibration/intrinsics_calibration.h"
#include "calibration/linearity_calibration.h"
#include "calibration/luminance_calibration.h"
#include "calibration/noise_calibration.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam {
namespace {

using capture::CalibrationTarget;
using capture::CalibrationTargetOptions;
using capture::CalibrationTargetStack;

CalibrationTargetStack target(CalibrationTarget kind, CalibrationTargetOptions options = {}) {
  options.target = kind;
  auto stacks = capture::simulateCalibrationTarget(options);
  EXPECT_TRUE(stacks) << stacks.error().message;
  return std::move(stacks->front());
}

// The stack's frames as the procedures take them, named "target/frame-NN.png".
std::vector<calibration::InputFrame> inputFrames(const CalibrationTargetStack& stack) {
  std::vector<calibration::InputFrame> frames;
  for (std::size_t i = 0; i < stack.frames.size(); ++i) {
    frames.push_back({.frame = stack.frames[i],
                      .spec = stack.manifest.frames[i],
                      .name = "target/" + stack.manifest.frames[i].file,
                      .bit_depth = 16,
                      .stack = 0});
  }
  return frames;
}

// The simulated sensor's levels (capture::SensorModel defaults).
const calibration::SensorLevels kLevels{.black_level_dn = 64, .saturation_dn = 4000};

// ---- dark -------------------------------------------------------------------------------------

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

// ---- flat -------------------------------------------------------------------------------------

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

// ---- linearity ----------------------------------------------------------------------------------

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

// ---- noise ------------------------------------------------------------------------------------

TEST(CalibrateNoise, ThePhotonTransferCurveGivesReadNoiseAndGain) {
  const CalibrationTargetStack ptc = target(CalibrationTarget::kNoise);
  const auto result = calibration::calibrateNoise(
      inputFrames(ptc), kLevels,
      calibration::centralRoi(ptc.frames[0].width(), ptc.frames[0].height()));
  ASSERT_TRUE(result) << result.error().message;
  // Truth: the simulated sensor's 0.5 DN/e- and 2 DN read noise, which quantisation to whole DN
  // raises to 2.02 DN. Each is checked to 4 standard uncertainties of the fit (a 6e-5 false
  // failure rate), and those uncertainties must be small enough for the merge (< 3 %).
  const double gain = ptc.truth["dn_per_electron"].get<double>();
  const double read = ptc.truth["read_noise_with_quantisation_dn"].get<double>();
  EXPECT_NEAR(result->model.dn_per_electron, gain, 4 * result->dn_per_electron_u);
  EXPECT_NEAR(result->model.read_noise_dn, read, 4 * result->read_noise_u_dn);
  EXPECT_LT(result->dn_per_electron_u / gain, 0.03);
  EXPECT_LT(result->read_noise_u_dn / read, 0.03);
  EXPECT_EQ(result->points.size(), 8u);
}

TEST(CalibrateNoise, PairsAtTooFewExposuresAreAnError) {
  const CalibrationTargetStack ptc = target(CalibrationTarget::kNoise);
  const auto frames = inputFrames(ptc);
  const auto result = calibration::calibrateNoise(std::span(frames).first(4), kLevels,
                                                  calibration::centralRoi(320, 256));
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("needs pairs at 3 or more exposures"), std::string::npos);
}

// ---- luminance --------------------------------------------------------------------------------

Calibration sensorCalibration() {
  Calibration calibration;
  calibration.black_level_dn = kLevels.black_level_dn;
  calibration.saturation_dn = kLevels.saturation_dn;
  calibration.reference_f_number = 8;
  calibration.noise = NoiseModel{.read_noise_dn = 2, .dn_per_electron = 0.5};
  return calibration;
}

calibration::Roi truthRoi(const CalibrationTargetStack& stack) {
  const auto& r = stack.truth["roi"];
  return {r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>()};
}

TEST(CalibrateLuminance, RecoversKWithTheMetersUncertainty) {
  const CalibrationTargetOptions options;
  const CalibrationTargetStack patch = target(CalibrationTarget::kLuminance);
  const FloatImage flat =
      capture::naturalVignetting(options.width, options.height, options.horizontal_fov_deg);
  const double reference = patch.truth["reference_cd_m2"].get<double>();
  const auto result = calibration::calibrateLuminance(
      inputFrames(patch), sensorCalibration(), &flat, truthRoi(patch),
      {.readings_cd_m2 = {reference * 0.995, reference * 1.005}});
  ASSERT_TRUE(result) << result.error().message;
  // The merge is unbiased to 0.1 % (HdrMerge tests) and the region's mean of 16k pixels carries
  // 0.01 % noise: K to 0.3 %.
  const double k = patch.truth["luminance_factor"].get<double>();
  EXPECT_NEAR(result->luminance_factor / k, 1.0, 0.003);
  // The budget: ±2 % meter read as rectangular (1.155 %), readings ±0.5 % (0.5 %), a flat patch
  // (no non-uniformity beyond noise), noise ~0.01 %.
  EXPECT_NEAR(result->relative.meter, 0.02 / std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(result->relative.readings, 0.005, 1e-4);
  EXPECT_LT(result->relative.non_uniformity, 0.002);
  EXPECT_LT(result->relative.noise, 0.001);
  EXPECT_NEAR(result->luminance_factor_u / result->luminance_factor,
              std::hypot(0.02 / std::sqrt(3.0), 0.005), 0.002);
}

TEST(CalibrateLuminance, AReferenceSaturatedInEveryFrameIsAnError) {
  const CalibrationTargetStack patch = target(CalibrationTarget::kLuminance);
  std::vector<calibration::InputFrame> frames = inputFrames(patch);
  frames.erase(frames.begin(), frames.end() - 1);  // the longest exposure only
  const auto result = calibration::calibrateLuminance(
      std::move(frames), sensorCalibration(), nullptr, truthRoi(patch), {.readings_cd_m2 = {5000}});
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("saturated in every frame"), std::string::npos);
}

// ---- intrinsics -------------------------------------------------------------------------------

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
