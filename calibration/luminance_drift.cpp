#include "calibration/luminance_drift.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "calibration/calibration_inputs.h"
#include "calibration/calibration_parts.h"
#include "calibration/prior_calibration.h"
#include "core/atomic_file.h"

namespace glarecam::calibration {

Status DriftCheckOptions::validate() const {
  if (calibrations.empty())
    return badInput(
        "calibrate luminance --check: give the calibration to check with --calibration");
  if (stacks.empty())
    return badInput("calibrate luminance --check: give the recorded field stack(s) to check");
  if (!roi)
    return badInput("calibrate luminance --check: give the reference patch's region with --roi");
  return reference.validate();
}

bool DriftReport::exceedsTwiceUncertainty() const { return std::abs(drift) > 2 * drift_u; }

Status DriftReport::verdict() const {
  if (!exceedsTwiceUncertainty()) return {};
  return fail(ErrorCode::kInternal,
              fmt::format("calibrate luminance --check: the drift {:+.2f} % exceeds twice its "
                          "uncertainty ({:.2f} %): recalibrate K (docs/calibration.md)",
                          100 * drift, 100 * drift_u));
}

nlohmann::json DriftReport::toJson() const {
  return {{"stacks", stacks},
          {"captured_at", captured_at},
          {"luminance_factor", luminance_factor},
          {"measured_luminance_factor", measured_luminance_factor},
          {"drift", drift},
          {"drift_u", drift_u}};
}

std::string DriftReport::logLine() const {
  return fmt::format("{},{},{:.8g},{:.8g},{:.6f},{:.6f}\n", captured_at, stacks.front(),
                     luminance_factor, measured_luminance_factor, drift, drift_u);
}

Status appendDriftLog(const std::filesystem::path& log, const DriftReport& report) {
  std::string text;
  if (std::filesystem::exists(log)) {
    std::ifstream in(log);
    text.assign(std::istreambuf_iterator<char>(in), {});
  } else {
    text = kDriftLogHeader;
  }
  text += report.logLine();
  return writeFileAtomic(log, text);
}

Result<DriftReport> checkLuminanceDrift(const DriftCheckOptions& options) {
  GLARECAM_CHECK(options.validate());
  CalibrationInputs inputs;
  GLARECAM_ASSIGN(inputs, readCalibrationInputs(options.stacks, options.show_progress));
  PriorCalibration prior;
  GLARECAM_ASSIGN(prior, readPriorCalibration(options.calibrations, inputs));
  if (!prior.luminance_factor)
    return badInput("calibrate luminance --check: the calibration has no luminance_factor");
  if (!(*prior.luminance_factor > 0 && std::isfinite(*prior.luminance_factor))) {
    return badInput(fmt::format(
        "calibrate luminance --check: the calibration's luminance_factor {:g} must be a positive "
        "finite number",
        *prior.luminance_factor));
  }
  if (prior.luminance_factor_u &&
      !(*prior.luminance_factor_u >= 0 && std::isfinite(*prior.luminance_factor_u))) {
    return badInput(fmt::format(
        "calibrate luminance --check: the calibration's luminance_factor_u {:g} must be a "
        "non-negative finite number",
        *prior.luminance_factor_u));
  }
  LuminanceCalibration measured;
  GLARECAM_ASSIGN(measured, measureLuminance(inputs, prior, options.roi, options.reference));
  const double k = *prior.luminance_factor;
  // Both Ks are uncertain: the check's own budget and the calibration's u(K), in quadrature.
  const double u_k = prior.luminance_factor_u.value_or(0.0) / k;
  DriftReport report{.stacks = inputs.stack_paths,
                     .captured_at = inputs.latest_capture,
                     .luminance_factor = k,
                     .measured_luminance_factor = measured.luminance_factor,
                     .drift = measured.luminance_factor / k - 1,
                     .drift_u = std::hypot(measured.relative.combined(), u_k)};
  if (options.log) GLARECAM_CHECK(appendDriftLog(*options.log, report));
  return report;
}

}  // namespace glarecam::calibration
