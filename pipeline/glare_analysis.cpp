#include "pipeline/glare_analysis.h"

namespace glarecam::pipeline {

Result<GlareAnalysis> analyseGlare(const calibration::MergedImage& merged,
                                   const calibration::CameraModel& camera,
                                   const LuminancePeak& peak, const GlareAnalysisOptions& options) {
  GlareAnalysis analysis;
  const auto at = [&](double level, double level_relative_uncertainty) {
    return measureGlareEllipse(merged, camera, peak, level, level_relative_uncertainty);
  };
  if (options.limit_cd_m2) {
    EllipseMeasurement limit;
    GLARECAM_ASSIGN(limit, at(*options.limit_cd_m2, 0.0));
    analysis.limit = std::move(limit);
  }
  const double half_maximum = peak.value_cd_m2 / 2;
  const bool peak_is_bound =
      peak.method == PeakMethod::kLowerBound || peak.method == PeakMethod::kUpperBound;
  if (peak_is_bound) {
    analysis.fwhm = {half_maximum, EllipseStatus::kPeakIsBound, std::nullopt};
  } else {
    GLARECAM_ASSIGN(analysis.fwhm, at(half_maximum, peak.relative_uncertainty));
  }
  for (const double threshold : options.thresholds_cd_m2) {
    EllipseMeasurement measurement;
    GLARECAM_ASSIGN(measurement, at(threshold, 0.0));
    analysis.thresholds.push_back(std::move(measurement));
  }
  return analysis;
}

}  // namespace glarecam::pipeline
