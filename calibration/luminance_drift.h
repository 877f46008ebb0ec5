// `glarecam calibrate luminance --check` (docs/calibration.md, "Checking K in the field"): K
// measured again on a reference patch of known luminance in a field stack, the same way the
// luminance part measures it (calibration_parts.h), against the calibration's K. The drift is
// measured / K - 1; its standard uncertainty combines the check's own budget and the
// calibration's u(K) in quadrature. A drift beyond twice its uncertainty calls for measuring K
// again. Each check can be appended to a CSV log, one line a check.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/frame_statistics.h"
#include "calibration/luminance_calibration.h"
#include "core/error.h"

namespace glarecam::calibration {

struct DriftCheckOptions {
  std::vector<std::string> stacks;           // the field stack(s) showing the patch, as given
  std::vector<std::string> calibrations;     // the calibration to check, merged in order
  std::optional<Roi> roi;                    // the patch's region (required)
  LuminanceReference reference;              // the meter's reading(s) of the patch
  std::optional<std::filesystem::path> log;  // CSV file the check's line is appended to
  bool show_progress = false;                // while reading the stacks, on stderr
  Status validate() const;  // a calibration, stacks and the region given; the reference's
};

struct DriftReport {
  std::vector<std::string> stacks;       // as given
  std::string captured_at;               // the newest of the stacks' (ISO 8601), or empty
  double luminance_factor = 0;           // the calibration's K
  double measured_luminance_factor = 0;  // K measured on the patch
  double drift = 0;                      // measured / K - 1
  double drift_u = 0;                    // its standard uncertainty (relative)

  bool exceedsTwiceUncertainty() const;  // |drift| > 2 drift_u: recalibrate K
  // kInternal (exit 1) "... recalibrate K" when the drift exceeds twice its uncertainty, so that a
  // scheduled check can act on its exit status; else nothing.
  Status verdict() const;
  nlohmann::json toJson() const;
  std::string logLine() const;  // the CSV log's line for this check, with its newline
};

inline constexpr std::string_view kDriftLogHeader =
    "captured_at,stack,luminance_factor,measured_luminance_factor,drift,drift_u\n";

// Measures, appends to options.log when given, and warns when the drift exceeds twice its
// uncertainty.
Result<DriftReport> checkLuminanceDrift(const DriftCheckOptions& options);

// Appends the report's line to the CSV log (created with kDriftLogHeader), atomically.
Status appendDriftLog(const std::filesystem::path& log, const DriftReport& report);

}  // namespace glarecam::calibration
