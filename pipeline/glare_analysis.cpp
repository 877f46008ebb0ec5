#include "pipeline/glare_analysis.h"

namespace glarecam::pipeline {

GlareAnalysis analyseGlare(const calibration::MergedImage& merged,
                           const calibration::CameraModel& camera, const LuminancePeak& peak,
                           const GlareAnalysisOptions& options) {
  const auto at = [&](double level, double level_relative_uncertainty) {
    return measureGlareEllipse(merged, camera, peak, level, level_relative_uncertainty);
  };
  GlareAnalysis analysis;
  const double scale_u = options.scale_relative_uncertainty;
  if (options.limit_cd_m2) analysis.limit = at(*options.limit_cd_m2, scale_u);
  const double half_maximum = peak.value_cd_m2 / 2;
  const bool peak_is_bound =
      peak.method == PeakMethod::kLowerBound || peak.method == PeakMethod::kUpperBound;
  analysis.fwhm = peak_is_bound
                      ? EllipseMeasurement{half_maximum, EllipseStatus::kPeakIsBound, std::nullopt}
                      : at(half_maximum, peak.relative_uncertainty);
  for (const double threshold : options.thresholds_cd_m2)
    analysis.thresholds.push_back(at(threshold, scale_u));
  return analysis;
}

}  // namespace glarecam::pipeline
