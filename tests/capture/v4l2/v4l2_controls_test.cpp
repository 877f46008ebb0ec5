// The V4L2 control mapping: exposures and gains to control codes within their range and step,
// auto switched off first, and frames settling after a write.
#include "capture/v4l2/v4l2_controls.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glarecam::capture {
namespace {

TEST(V4l2Controls, ExposureRoundsToTheNearest100Microseconds) {
  const V4l2ControlRange range{1, 10000, 1, 100};
  EXPECT_EQ(exposureSetting(1049.0, range).code, 10);
  EXPECT_EQ(exposureSetting(1049.0, range).exposure_us, 1000.0);  // the applied value
  EXPECT_EQ(exposureSetting(1050.0, range).code, 11);
  EXPECT_EQ(exposureSetting(1050.0, range).exposure_us, 1100.0);
  EXPECT_EQ(exposureSetting(20'000.0, range).exposure_us, 20'000.0);
}

TEST(V4l2Controls, ExposureClampsToTheRangeAndItsStep) {
  const V4l2ControlRange range{3, 2000, 4, 3};  // codes 3, 7, 11, ..., 1999 (2000 is off-grid)
  EXPECT_EQ(exposureSetting(1000.0, range).code, 11);  // 10 → nearest grid point 11
  EXPECT_EQ(exposureSetting(1000.0, range).exposure_us, 1100.0);
  EXPECT_EQ(exposureSetting(10.0, range).code, 3);  // below min
  EXPECT_EQ(exposureSetting(1e9, range).code, 1999);
  EXPECT_EQ(exposureSetting(1e9, range).exposure_us, 199'900.0);
}

TEST(V4l2Controls, ExposureIsNeverZero) {
  EXPECT_EQ(exposureSetting(10.0, {0, 100, 1, 0}).code, 1);
  EXPECT_EQ(exposureSetting(10.0, {0, 100, 5, 0}).code, 5);
}

TEST(V4l2Controls, SnapsToTheGrid) {
  EXPECT_EQ(snapToControl(10.0, {0, 10, 3, 0}), 9);
  EXPECT_EQ(snapToControl(4.4, {0, 10, 3, 0}), 3);
  EXPECT_EQ(snapToControl(4.6, {0, 10, 3, 0}), 6);
  EXPECT_EQ(snapToControl(-7.0, {-5, 5, 1, 0}), -5);
}

TEST(V4l2Controls, GainIsLinearAboveTheMinimum) {
  const V4l2GainControl gain{V4l2Control::kAnalogueGain, {16, 256, 1, 16}};
  EXPECT_EQ(gainSetting(0.0, gain).code, 16);
  EXPECT_EQ(gainSetting(0.0, gain).gain_db, 0.0);
  EXPECT_EQ(gainSetting(20.0 * std::log10(2.0), gain).code, 32);
  EXPECT_NEAR(gainSetting(20.0 * std::log10(2.0), gain).gain_db, 6.0206, 1e-4);
  // 1 dB → 17.95 → code 18, which is 1.023 dB: the applied value is reported.
  EXPECT_EQ(gainSetting(1.0, gain).code, 18);
  EXPECT_NEAR(gainSetting(1.0, gain).gain_db, 20.0 * std::log10(18.0 / 16.0), 1e-12);
  EXPECT_EQ(gainSetting(40.0, gain).code, 256);  // clamped to max
  EXPECT_EQ(gainSetting(-3.0, gain).code, 16);   // clamped to min
  EXPECT_NEAR(gainDbFromCode(256, gain), 20.0 * std::log10(16.0), 1e-12);
}

TEST(V4l2Controls, GainWithoutAUnityCodeOffersZeroDecibelsOnly) {
  const V4l2GainControl gain{V4l2Control::kGain, {0, 255, 1, 64}};
  EXPECT_EQ(gainSetting(12.0, gain).code, 0);
  EXPECT_EQ(gainSetting(12.0, gain).gain_db, 0.0);
  V4l2ControlSet controls;
  controls.exposure = {1, 5000, 1, 100};
  controls.gain = gain;
  EXPECT_EQ(limitsOf(controls).max_gain_db, 0.0);
}

TEST(V4l2Controls, LimitsAreInMicroseconds) {
  V4l2ControlSet controls;
  controls.exposure = {2, 5000, 1, 100};
  controls.gain = V4l2GainControl{V4l2Control::kAnalogueGain, {16, 160, 1, 16}};
  const auto limits = limitsOf(controls);
  EXPECT_EQ(limits.min_exposure_us, 200.0);
  EXPECT_EQ(limits.max_exposure_us, 500'000.0);
  EXPECT_EQ(limits.exposure_step_us, 100.0);
  EXPECT_EQ(limits.min_gain_db, 0.0);
  EXPECT_NEAR(limits.max_gain_db, 20.0, 1e-12);
}

TEST(V4l2Controls, OneWriteSwitchesAutoOffFirst) {
  V4l2ControlSet controls;
  controls.exposure = {1, 5000, 1, 100};
  controls.has_exposure_auto = true;
  controls.has_auto_gain = true;
  controls.gain = V4l2GainControl{V4l2Control::kAnalogueGain, {16, 256, 1, 16}};
  const auto write = controlWrite(controls, {1234.0, 6.0206});
  ASSERT_EQ(write.values.size(), 4u);
  EXPECT_EQ(write.values[0].control, V4l2Control::kExposureAuto);
  EXPECT_EQ(write.values[0].value, kExposureAutoManual);
  EXPECT_EQ(write.values[1].control, V4l2Control::kAutoGain);
  EXPECT_EQ(write.values[1].value, 0);
  EXPECT_EQ(write.values[2].control, V4l2Control::kExposureAbsolute);
  EXPECT_EQ(write.values[2].value, 12);
  EXPECT_EQ(write.values[3].control, V4l2Control::kAnalogueGain);
  EXPECT_EQ(write.values[3].value, 32);

  // The applied values come from the read-back, not from what was written.
  auto applied = appliedControls(
      controls, {{V4l2Control::kExposureAbsolute, 13}, {V4l2Control::kAnalogueGain, 64}});
  ASSERT_TRUE(applied) << applied.error().message;
  EXPECT_EQ(applied->exposure_us, 1300.0);
  EXPECT_NEAR(applied->gain_db, 20.0 * std::log10(4.0), 1e-12);
}

TEST(V4l2Controls, FramesSettleAfterTheWrite) {
  const auto gate = settleGate(10, 3);
  EXPECT_FALSE(gate.settled(10));
  EXPECT_FALSE(gate.settled(12));
  EXPECT_TRUE(gate.settled(13));
  EXPECT_TRUE(settleGate(10, 0).settled(10));
}

}  // namespace
}  // namespace glarecam::capture
