#include "capture/bracketing.h"

#include <algorithm>
#include <cmath>

namespace glarecam::capture {

Status BracketOptions::validate() const {
  if (min_frames < 1 || min_frames > 64)
    return badInput("bracket: min_frames must be between 1 and 64");
  if (!(max_step_ratio > 1.0)) return badInput("bracket: max_step_ratio must exceed 1");
  if (!(peak_fraction > 0 && peak_fraction <= 1 && background_fraction > 0 &&
        background_fraction <= 1)) {
    return badInput("bracket: fractions must be in (0, 1]");
  }
  if (!(min_exposure_us > 0 && max_exposure_us >= min_exposure_us && exposure_step_us > 0)) {
    return badInput("bracket: exposure limits must be positive and ordered");
  }
  return {};
}

double roundedExposureUs(double exposure_us, double step_us, double min_us, double max_us) {
  return std::clamp(std::round(exposure_us / step_us) * step_us, min_us, max_us);
}

Result<BracketPlan> planBracket(double peak_dn_per_us, double background_dn_per_us,
                                double usable_range_dn, const BracketOptions& options) {
  GLARECAM_CHECK(options.validate());
  if (!(peak_dn_per_us > 0 && background_dn_per_us > 0 && usable_range_dn > 0) ||
      !std::isfinite(peak_dn_per_us) || !std::isfinite(background_dn_per_us)) {
    return badInput("bracket: signal rates and range must be positive and finite");
  }
  background_dn_per_us = std::min(background_dn_per_us, peak_dn_per_us);
  BracketPlan plan;
  double shortest = options.peak_fraction * usable_range_dn / peak_dn_per_us;
  double longest = options.background_fraction * usable_range_dn / background_dn_per_us;
  // Clipped only if even the camera's shortest exposure saturates the peak.
  plan.peak_clipped = peak_dn_per_us * options.min_exposure_us >= usable_range_dn;
  plan.background_underexposed = longest > options.max_exposure_us;
  shortest = std::clamp(shortest, options.min_exposure_us, options.max_exposure_us);
  longest = std::clamp(longest, shortest, options.max_exposure_us);
  const double span = longest / shortest;
  const int steps =
      std::max(options.min_frames - 1,
               static_cast<int>(std::ceil(std::log(span) / std::log(options.max_step_ratio))));
  for (int i = 0; i <= steps; ++i) {
    const double exposure =
        shortest * std::pow(span, steps == 0 ? 0.0 : static_cast<double>(i) / steps);
    // Round to the camera's resolution, never beyond its limits: this is the applied value.
    plan.exposures_us.push_back(roundedExposureUs(
        exposure, options.exposure_step_us, options.min_exposure_us, options.max_exposure_us));
  }
  return plan;
}

}  // namespace glarecam::capture
