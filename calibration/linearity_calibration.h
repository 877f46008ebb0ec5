// `glarecam calibrate linearity`: a ramp of exposures of a steady source. The mean signal above
// black in a region is fitted, through the origin, on the ramp's lower part (where every sensor
// is linear); each point's deviation from that line shows where the response bends. The usable
// range ends where the deviation first exceeds the tolerance: that DN becomes saturation_dn, the
// level above which the merge treats a reading as saturated.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "calibration/flat_calibration.h"
#include "calibration/frame_statistics.h"
#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// The line is fitted on points whose signal lies between these fractions of the largest
// signal of the ramp: above the noise floor, below any bend (sensors bend only in their top
// quarter: EMVA 1288 fits its linearity between 5 % and 95 % and reports the deviation).
inline constexpr double kLinearFitLowFraction = 0.05, kLinearFitHighFraction = 0.5;
inline constexpr double kDefaultLinearityTolerance = 0.01;  // 1 %
inline constexpr std::size_t kMinRampPoints = 4;

struct RampPoint {
  double exposure_us = 0;
  double signal_dn = 0;  // mean above black in the region
  double deviation = 0;  // signal / line - 1
};

struct LinearityCalibration {
  double slope_dn_per_us = 0;  // at the ramp's gain
  std::vector<RampPoint> points;
  double linear_from_dn = 0, linear_to_dn = 0;  // usable range, raw DN (black included)
  double max_deviation = 0;                     // within the usable range
  double saturation_dn = 0;                     // = linear_to_dn
  bool bend_found = false;  // false: the ramp never left the tolerance (saturation is a bound)
  double tolerance = kDefaultLinearityTolerance;
};

// The tolerance, a fraction, must be in (0, 1).
Status checkLinearityTolerance(double tolerance);

Result<LinearityCalibration> calibrateLinearity(std::span<const InputFrame> frames,
                                                double black_level_dn, const Roi& roi,
                                                double tolerance);

nlohmann::json linearityValues(const LinearityCalibration& linearity);

}  // namespace glarecam::calibration
