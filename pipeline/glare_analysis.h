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
  // The relative standard uncertainty of the image's absolute scale that the ellipses at fixed
  // levels inherit as their level's: u(E)/E for an image referred to a reference illuminance
  // (docs/method.md). A scale error moves the contour at a fixed level exactly as the opposite
  // error of the level does; the FWHM, at a fraction of the image's own peak, is immune to it.
  double scale_relative_uncertainty = 0;
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
