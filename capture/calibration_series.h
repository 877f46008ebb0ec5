// Capturing the stacks a calibration part is measured from (`glarecam calibrate PART --camera
// URI`, docs/calibration.md): a bracket of fixed exposures (a value repeated gives several frames
// at that exposure: dark frames, photon transfer pairs), once, or for the checkerboard's poses
// several times a set interval apart while the operator moves the board. Each stack is written
// to the series' directory as <id>/ (the calibration procedures read them back, and the part's
// provenance names them), so a capture is kept with the part it made.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace glarecam::capture {

// Frames one stack of a series may take (a photon transfer curve of 64 pairs, say).
inline constexpr std::size_t kMaxSeriesFrames = 256;

struct CalibrationSeriesOptions {
  std::string camera_uri;            // camera_registry.h
  std::vector<double> exposures_us;  // one stack's frames, in order
  double gain_db = 0;
  int views = 1;                    // stacks to capture (board poses)
  double view_interval_s = 10;      // between them, for the operator to move the board
  std::filesystem::path directory;  // where the stacks go
  bool show_progress = false;       // on stderr
  Status validate() const;  // 1 to kMaxSeriesFrames exposures, views >= 1, interval 0 to 3600 s
};

// The stacks' paths, in the order captured.
Result<std::vector<std::filesystem::path>> captureCalibrationSeries(
    const CalibrationSeriesOptions& options);

}  // namespace glarecam::capture
