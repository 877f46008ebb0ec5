// What every `glarecam calibrate` procedure starts from: the frames of its input stacks (read
// without needing a calibration, all of one camera and size), and what it ends with: its part
// as a glarecam.calibration/1 document with the part's provenance (the stacks, when and how).
// The values measured before the procedure are in prior_calibration.h.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "calibration/calibration_file.h"
#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/stack_io.h"

namespace glarecam::calibration {

struct CalibrationInputs {
  std::vector<Stack> stacks;             // as read; their frames moved into `frames`
  std::vector<std::string> stack_paths;  // as given
  std::vector<InputFrame> frames;        // every frame of every stack, in order
  CameraIdentity camera;
  int width = 0, height = 0;   // every frame's size (refused otherwise)
  std::string latest_capture;  // the newest captured_at of the stacks (ISO 8601), or empty
};

// Reads the stacks (progress on stderr when `show_progress`); refuses stacks of different cameras
// (serials) or frame sizes.
Result<CalibrationInputs> readCalibrationInputs(std::span<const std::string> stack_paths,
                                                bool show_progress);

// The largest value the frames' pixel format holds (MonoN: 2^N - 1; else the files' bit depth).
double formatMaxDn(const CalibrationInputs& inputs);

// A part's document: the inputs' camera, `values`, and parts[part] with its provenance.
CalibrationDocument partDocument(const CalibrationInputs& inputs, const std::string& part,
                                 const std::string& method, nlohmann::json values);

// Next to `out` ("rig1/dark.json" + "-dark.exr" -> "rig1/dark-dark.exr"): a file a part writes.
std::filesystem::path companionFile(const std::filesystem::path& out, const std::string& suffix);

}  // namespace glarecam::calibration
