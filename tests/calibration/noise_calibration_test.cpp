// The noise calibration gives the read noise and gain of a simulated target from the photon
// transfer curve, and refuses pairs at too few exposures.
#include "calibration/noise_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace glarecam
