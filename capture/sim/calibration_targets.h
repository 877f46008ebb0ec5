// Calibration targets of the simulated rig, each with its ground truth, for the
// `glarecam calibrate` procedures to recover (tests, demos, docs/calibration.md):
//   dark       lens capped: black level, a fixed pattern, hot pixels with dark current
//   flat       a uniform source through the lens' natural vignetting (cos⁴ of the field angle)
//   linearity  a ramp of exposures of a uniform source, the response bending near saturation
//   noise      pairs of frames of a uniform source at several exposures (photon transfer)
//   luminance  a reference patch of known luminance in front of a darker background
//   board      a checkerboard in several poses seen through a distorted lens (one stack a view)
// Frames go through the simulated sensor (sensor_model.h); with the source at K cd/m² a frame's
// signal in DN equals its exposure in µs (before vignetting), which keeps the plans readable.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "capture/sim/sensor_model.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

enum class CalibrationTarget { kDark, kFlat, kLinearity, kNoise, kLuminance, kBoard };

Result<CalibrationTarget> parseCalibrationTarget(std::string_view name);
std::string_view calibrationTargetName(CalibrationTarget target);

// The camera (SimulatedCameraModel) and the target in front of it. A lab camera: 320x256 frames
// through a distorted lens (which intrinsics must find).
struct CalibrationTargetOptions : SimulatedCameraModel {
  CalibrationTargetOptions() {
    width = 320;
    height = 256;
    distortion = {-0.12, 0.05, 0.001, -0.0005, 0.0};  // k1 k2 p1 p2 k3
  }

  CalibrationTarget target = CalibrationTarget::kDark;
  std::string serial = "SIM-0001";
  // dark
  int hot_pixels = 12;
  double fixed_pattern_dn = 0.5;  // standard deviation of the per-pixel offset
  // linearity: above `knee` DN of signal the response loses curvature · (s - knee)² DN
  double nonlinearity_knee_dn = 3000.0;
  double nonlinearity_curvature_per_dn = 1e-4;
  // luminance
  double reference_cd_m2 = 5000.0;
  double background_cd_m2 = 300.0;
  // board
  int board_inner_columns = 9, board_inner_rows = 6;
  double board_square_mm = 30.0;
  int board_views = 12;
};

struct CalibrationTargetStack {
  StackManifest manifest;  // no calibration block: that is what the procedures produce
  std::vector<RawFrame> frames;
  nlohmann::json truth;  // glarecam.truth/1 with the target's true values
};

// One stack, or one per view for the board.
Result<std::vector<CalibrationTargetStack>> simulateCalibrationTarget(
    const CalibrationTargetOptions& options);

// Writes the stacks as <directory>/<target>[-NN], each with its truth.json; returns their paths.
// `show_progress`: a progress line over the stacks on stderr (the board's 12 views take a while).
Result<std::vector<std::filesystem::path>> writeCalibrationTargetStacks(
    const std::filesystem::path& directory, CalibrationTarget target,
    const std::vector<CalibrationTargetStack>& stacks, bool show_progress = false);

// What a target puts in front of the lens, in cd/m² (the `sim:target=NAME` camera looks at it):
// the scene only, without the recorded stacks' sensor defects (fixed pattern, hot pixels, the
// response bend); the board in its first pose.
Result<FloatImage> calibrationTargetScene(const CalibrationTargetOptions& options);

// The simulated lens' flat field: cos⁴ of each pixel's field angle (1 at the principal point).
FloatImage naturalVignetting(int width, int height, double horizontal_fov_deg);

}  // namespace glarecam::capture
