#include "capture/capture_config.h"

namespace glarecam::capture {

CameraOptions cameraOptions(const CaptureConfig& config) {
  CameraOptions options;
  options.pixel_format = config.pixel_format;
  options.max_frame_retries = config.max_frame_retries;
  options.genicam_features = config.genicam_features;
  return options;
}

CaptureSettings captureSettings(const CaptureConfig& config) {
  CaptureSettings settings;
  settings.exposures_us = config.exposures_us;
  settings.gain_db = config.gain_db;
  settings.optics.f_number = config.f_number;
  settings.optics.nd_transmission = config.nd_transmission;
  return settings;
}

}  // namespace glarecam::capture
