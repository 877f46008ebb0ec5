// Which glare ellipses a luminance image gets (docs/method.md): the limit ellipse at the glare
// limit (when there is one), the FWHM ellipse at half the robust maximum (luminance_peak.h;
// its level inherits the maximum's uncertainty), one ellipse per extra threshold (a threshold
// sweep), and the contour ladder ("Reference illuminance and the contour ladder"): the ellipses
// at the fixed levels 1, 2.15 and 4.64 × 10ⁿ cd/m² from 10 000 cd/m² up to below the maximum,
// with the limit and half-maximum rungs among them, ascending. Each is a glare_ellipse.h
// measurement; all are measured together (measureGlareEllipses: one flood of the whole image).
// Pure function; no I/O.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "pipeline/glare_ellipse.h"

namespace glarecam::pipeline {

// The ladder's lowest rung and its steps per decade (the mantissas of its levels).
inline constexpr double kLadderLowestCdM2 = 1e4;
inline constexpr double kLadderMantissas[] = {1.0, 2.15, 4.64};
// At most this many fixed rungs (from 10 000 cd/m², 10¹⁴ cd/m²: far beyond any sun's reflection).
inline constexpr std::size_t kMaxLadderRungs = 30;

// The ladder's fixed levels below `peak_cd_m2`, ascending (none when it is not above 10 000).
std::vector<double> ladderLevelsCdM2(double peak_cd_m2);

// Whether `level_cd_m2` is one of the ladder's fixed levels (to a relative 1e-9).
bool isLadderLevel(double level_cd_m2);

enum class ContourKind { kLadder, kLimit, kHalfMaximum };
const char* toString(ContourKind kind);  // "ladder", "limit", "half_maximum"
std::optional<ContourKind> contourKindFromString(std::string_view text);

// One rung of the ladder: its kind and the ellipse at its level (or why there is none).
struct ContourRung {
  ContourKind kind = ContourKind::kLadder;
  EllipseMeasurement measurement;
};

struct GlareAnalysisOptions {
  std::optional<double> limit_cd_m2;     // the α curve's limit or a constant threshold
  std::vector<double> thresholds_cd_m2;  // extra levels, each positive
  // The relative standard uncertainty of the image's absolute scale that the ellipses at fixed
  // levels inherit as their level's: u(E)/E for an image referred to a reference illuminance
  // (docs/method.md). A scale error moves the contour at a fixed level exactly as the opposite
  // error of the level does; the FWHM, at a fraction of the image's own peak, is immune to it.
  double scale_relative_uncertainty = 0;
  // The contour ladder (off: `process --no-ladder`, and the benchmark's peer).
  bool ladder = true;
};

struct GlareAnalysis {
  std::optional<EllipseMeasurement> limit;  // when there is a limit
  EllipseMeasurement fwhm;
  std::vector<EllipseMeasurement> thresholds;  // in the order asked
  // The ladder's fixed rungs, the limit rung (when there is a limit) and the half-maximum rung,
  // by ascending level (a fixed rung before the limit or half maximum at the same level); empty
  // when the ladder is off. The limit and half-maximum rungs are the limit and FWHM ellipses.
  std::vector<ContourRung> ladder;
};

GlareAnalysis analyseGlare(const calibration::MergedImage& merged,
                           const calibration::CameraModel& camera, const LuminancePeak& peak,
                           const GlareAnalysisOptions& options);

}  // namespace glarecam::pipeline
