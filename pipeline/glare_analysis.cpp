#include "pipeline/glare_analysis.h"

#include <algorithm>
#include <cmath>

namespace glarecam::pipeline {

std::vector<double> ladderLevelsCdM2(double peak_cd_m2) {
  std::vector<double> levels;
  if (!std::isfinite(peak_cd_m2)) return levels;
  // In hundredths of the decade, so that the levels are exact: 21 500, not 21 500.000000000004.
  for (double hundredth = kLadderLowestCdM2 / 100; levels.size() < kMaxLadderRungs;
       hundredth *= 10) {
    for (const double mantissa : kLadderMantissas) {
      const double level = std::round(mantissa * 100) * hundredth;
      if (!(level < peak_cd_m2) || levels.size() == kMaxLadderRungs) return levels;
      levels.push_back(level);
    }
  }
  return levels;
}

bool isLadderLevel(double level_cd_m2) {
  constexpr double kRelativeTolerance = 1e-9;
  if (!(level_cd_m2 >= kLadderLowestCdM2 * (1 - kRelativeTolerance)) || !std::isfinite(level_cd_m2))
    return false;
  const double decade =
      std::pow(10.0, std::floor(std::log10(level_cd_m2 * (1 + kRelativeTolerance))));
  for (const double mantissa : kLadderMantissas)
    if (std::abs(level_cd_m2 - mantissa * decade) <= kRelativeTolerance * level_cd_m2) return true;
  return false;
}

const char* toString(ContourKind kind) {
  switch (kind) {
    case ContourKind::kLadder:
      return "ladder";
    case ContourKind::kLimit:
      return "limit";
    case ContourKind::kHalfMaximum:
      return "half_maximum";
  }
  return "unknown";
}

std::optional<ContourKind> contourKindFromString(std::string_view text) {
  for (ContourKind kind : {ContourKind::kLadder, ContourKind::kLimit, ContourKind::kHalfMaximum})
    if (text == toString(kind)) return kind;
  return std::nullopt;
}

GlareAnalysis analyseGlare(const calibration::MergedImage& merged,
                           const calibration::CameraModel& camera, const LuminancePeak& peak,
                           const GlareAnalysisOptions& options) {
  const double scale_u = options.scale_relative_uncertainty;
  const double half_maximum = peak.value_cd_m2 / 2;
  const bool peak_is_bound =
      peak.method == PeakMethod::kLowerBound || peak.method == PeakMethod::kUpperBound;
  // Every level in one list, measured together: the limit, the FWHM (unless the maximum is a
  // bound), the thresholds, the ladder's fixed rungs.
  std::vector<EllipseLevel> levels;
  if (options.limit_cd_m2) levels.push_back({*options.limit_cd_m2, scale_u});
  if (!peak_is_bound) levels.push_back({half_maximum, peak.relative_uncertainty});
  for (const double threshold : options.thresholds_cd_m2) levels.push_back({threshold, scale_u});
  const std::size_t first_rung = levels.size();
  if (options.ladder)
    for (const double level : ladderLevelsCdM2(peak.value_cd_m2))
      levels.push_back({level, scale_u});
  std::vector<EllipseMeasurement> measured = measureGlareEllipses(merged, camera, peak, levels);

  GlareAnalysis analysis;
  std::size_t next = 0;
  if (options.limit_cd_m2) analysis.limit = measured[next++];
  analysis.fwhm = peak_is_bound
                      ? EllipseMeasurement{half_maximum, EllipseStatus::kPeakIsBound, std::nullopt}
                      : measured[next++];
  for (std::size_t i = 0; i < options.thresholds_cd_m2.size(); ++i)
    analysis.thresholds.push_back(std::move(measured[next++]));
  if (!options.ladder) return analysis;
  for (std::size_t i = first_rung; i < measured.size(); ++i)
    analysis.ladder.push_back({ContourKind::kLadder, std::move(measured[i])});
  if (analysis.limit) analysis.ladder.push_back({ContourKind::kLimit, *analysis.limit});
  analysis.ladder.push_back({ContourKind::kHalfMaximum, analysis.fwhm});
  std::stable_sort(analysis.ladder.begin(), analysis.ladder.end(),
                   [](const ContourRung& a, const ContourRung& b) {
                     return a.measurement.level_cd_m2 < b.measurement.level_cd_m2;
                   });
  return analysis;
}

}  // namespace glarecam::pipeline
