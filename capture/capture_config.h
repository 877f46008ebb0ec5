// How to capture, as a rig's [capture] section (daemon/daemon_config.h reads it) or the options of
// `glarecam capture` say it: the bracket's exposures ("auto": metered, auto_bracket.h) and gain,
// the pixel format, the lens and filter a camera cannot know, retries, and a GenICam preset. The
// camera's options and the bracket's settings are made from it here, once, for every caller.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "capture/bracketer.h"
#include "capture/camera.h"

namespace glarecam::capture {

struct CaptureConfig {
  std::optional<std::vector<double>> exposures_us;  // none: auto-bracket
  double gain_db = 0.0;
  std::optional<std::string> pixel_format;  // GenICam name; default the deepest mono format
  std::optional<double> f_number;           // lens, when the camera cannot know it
  std::optional<double> nd_transmission;    // ND filter in front of the lens, (0, 1]
  int max_frame_retries = 5;                // incomplete or timed-out frames per exposure
  // A GenICam feature preset (firmware-config/genicam/): its file and the features it sets, for
  // aravis: cameras (CameraOptions::genicam_features).
  std::optional<std::filesystem::path> genicam_preset{};
  std::optional<std::string> genicam_features{};
};

// The options the camera is opened with.
CameraOptions cameraOptions(const CaptureConfig& config);

// The bracket's settings (exposures, gain, optics); the capture adds α, the geometry block and
// the calibration.
CaptureSettings captureSettings(const CaptureConfig& config);

}  // namespace glarecam::capture
