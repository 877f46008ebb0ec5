// How to capture, as a [capture] section or `glarecam capture`'s options say it: the camera's
// options and the bracket's settings made from it.
#include "capture/capture_config.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace glarecam::capture {
namespace {

TEST(CaptureConfig, ByDefaultTheBracketIsMeteredWithoutGain) {
  const CaptureConfig config;
  const CaptureSettings settings = captureSettings(config);
  EXPECT_FALSE(settings.exposures_us);  // auto-bracket
  EXPECT_EQ(settings.gain_db, 0.0);
  EXPECT_FALSE(settings.optics.f_number);
  EXPECT_FALSE(settings.optics.nd_transmission);
  EXPECT_EQ(cameraOptions(config), CameraOptions{});
}

TEST(CaptureConfig, TheCameraIsOpenedWithTheFormatRetriesAndPreset) {
  CaptureConfig config;
  config.pixel_format = "Mono12";
  config.max_frame_retries = 7;
  config.genicam_preset = "firmware-config/genicam/lab.conf";
  config.genicam_features = "Width=320 GammaEnable=false";
  const CameraOptions options = cameraOptions(config);
  EXPECT_EQ(options.pixel_format, "Mono12");
  EXPECT_EQ(options.max_frame_retries, 7);
  EXPECT_EQ(options.genicam_features, "Width=320 GammaEnable=false");
  EXPECT_EQ(options.frame_timeout_s, CameraOptions{}.frame_timeout_s);  // not the config's
}

TEST(CaptureConfig, TheBracketTakesTheExposuresGainAndOptics) {
  CaptureConfig config;
  config.exposures_us = std::vector<double>{10, 100, 1000};
  config.gain_db = 3;
  config.f_number = 8;
  config.nd_transmission = 0.001;
  const CaptureSettings settings = captureSettings(config);
  EXPECT_EQ(settings.exposures_us, (std::vector<double>{10, 100, 1000}));
  EXPECT_EQ(settings.gain_db, 3.0);
  EXPECT_EQ(settings.optics.f_number, 8.0);
  EXPECT_EQ(settings.optics.nd_transmission, 0.001);
  // What a capture adds itself is left alone.
  EXPECT_FALSE(settings.alpha_deg);
  EXPECT_FALSE(settings.calibration);
  EXPECT_FALSE(settings.geometry);
}

}  // namespace
}  // namespace glarecam::capture
