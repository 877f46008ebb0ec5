// The luminance calibration recovers a simulated luminance patch's K with the meter's
// uncertainty, and refuses a reference saturated in every frame.
#include "calibration/luminance_calibration.h"

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

}  // namespace
}  // namespace glarecam
