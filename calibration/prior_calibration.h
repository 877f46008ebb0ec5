// The values a calibration procedure builds on, measured before it: the black level and
// saturation (every procedure measuring signal above black), the principal point (where the flat
// field is normalised), the noise model, reference f-number and flat field (the luminance merge),
// and K with its uncertainty (the drift check). They come from the --calibration files, merged in
// order (glarecam.calibration/1 parts or bare calibration blocks), else from the first stack's
// own calibration block. A value that is absent or not a number is unknown.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include "calibration/calibration_inputs.h"
#include "calibration/flat_calibration.h"
#include "core/error.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

struct PriorCalibration {
  std::optional<double> black_level_dn, saturation_dn;
  std::optional<double> principal_x_px, principal_y_px;  // the intrinsics' cx, cy
  std::optional<double> reference_f_number;
  std::optional<double> luminance_factor, luminance_factor_u;  // K and its standard uncertainty
  std::optional<std::filesystem::path> flat_field;             // absolute
  // Every value as merged (paths absolute): the merge's calibration block is parsed from it.
  nlohmann::json source = nlohmann::json::object();
};

// The known values of a merged set of calibration values (paths already absolute).
PriorCalibration priorCalibrationOf(nlohmann::json values);

// The --calibration files merged in order, later values replacing earlier ones; none: the first
// stack's calibration block. Errors name the file.
Result<PriorCalibration> readPriorCalibration(std::span<const std::string> calibration_files,
                                              const CalibrationInputs& inputs);

// Black level and saturation; a missing saturation falls back to the largest value the frames'
// pixel format holds (formatMaxDn). `procedure` names the command in the error when the black
// level is unknown.
Result<SensorLevels> sensorLevels(const PriorCalibration& prior, const CalibrationInputs& inputs,
                                  const std::string& procedure);

// The values as a calibration for the merge (black, saturation, noise, reference f-number, flat
// field path), with `levels`; luminance_factor and intrinsics placeholders, which the merge does
// not need. Errors name "--calibration".
Result<Calibration> mergeCalibration(const PriorCalibration& prior, const SensorLevels& levels);

}  // namespace glarecam::calibration
