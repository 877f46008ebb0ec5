// Which glare ellipses a luminance image gets (docs/method.md): the limit ellipse at the glare
// limit (when there is one), the FWHM ellipse at half the robust maximum (luminance_peak.h;
// its level inherits the maximum's uncertainty), and one ellipse per extra threshold (a
// threshold sweep). Each is a glare_ellipse.h measurement. Pure function; no I/O.
#pragma once

#include <optional>
#include <vector>

#include "pipeline/glare_ellipse.h"

namespace glarecam::pipeline {

struct GlareAnalysisOptions {
  std::optional<double> limit_cd_m2;     // the α curve's limit or a constant threshold
  std::vector<double> thresholds_cd_m2;  // extra levels, each positive
};

struct GlareAnalysis {
  std::optional<EllipseMeasurement> limit;  // when there is a limit
  EllipseMeasurement fwhm;
  std::vector<EllipseMeasurement> thresholds;  // in the order asked
};

GlareAnalysis analyseGlare(const calibration::MergedImage& merged,
                           const calibration::CameraModel& camera, const LuminancePeak& peak,
                           const GlareAnalysisOptions& options);

}  // namespace glarecam::pipeline
