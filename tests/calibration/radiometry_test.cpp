// A frame's radiometry: the stack format's equation from DN to luminance, and the noise it
// implies.
#include "calibration/radiometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/radiometry_test_support.h"

namespace glarecam::calibration {
namespace {

using testing::basicCalibration;
using testing::frame;

TEST(Radiometry, FollowsTheStackFormatEquation) {
  const Calibration calibration = basicCalibration();
  // K (DN - B) / (t g tau) (N / N_ref)^2 with t = 200 µs, +6.0206 dB (x2), tau 0.5, f/11.
  const FrameRadiometry r =
      frameRadiometry(frame(200, 20 * std::log10(2.0), 11.0, 0.5), calibration);
  EXPECT_NEAR(r.scale_cd_m2_per_dn, 1500.0 / (200 * 2.0 * 0.5) * (11.0 / 8.0) * (11.0 / 8.0), 1e-9);
  EXPECT_NEAR(r.dn_per_electron, 1.0, 1e-12);  // 0.5 DN/e- amplified x2
  EXPECT_NEAR(r.read_noise_dn, 4.0, 1e-12);
  EXPECT_NEAR(r.min_signal_dn, 12.0, 1e-12);  // 3 sigma of the amplified read noise
}

}  // namespace
}  // namespace glarecam::calibration
