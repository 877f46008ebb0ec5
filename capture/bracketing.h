// Exposure bracketing: which exposure times cover a scene from its brightest pixel to its
// background. Pure logic on signal rates (DN per µs above black at the frame's gain), shared by
// the simulator and the camera backends' auto-bracket.
//  - the shortest exposure puts the brightest pixel at `peak_fraction` of the usable range
//    (margin for noise and for the camera rounding the exposure);
//  - the longest puts the background at `background_fraction` of the range (good SNR);
//  - exposures in between are log-spaced, at least `min_frames`, each step at most
//    `max_step_ratio` (one decade), all within the camera's limits.
#pragma once

#include <vector>

#include "core/error.h"

namespace glarecam::capture {

struct BracketOptions {
  int min_frames = 6;            // the SPF paper used six
  double max_step_ratio = 10.0;  // each frame valid over about one decade
  double peak_fraction = 0.7;
  double background_fraction = 0.5;
  double min_exposure_us = 10.0;
  double max_exposure_us = 2.0e6;
  double exposure_step_us = 1.0;  // the camera's exposure resolution
  Status validate() const;
};

struct BracketPlan {
  std::vector<double> exposures_us;      // ascending
  bool peak_clipped = false;             // even the camera's shortest exposure saturates the peak
  bool background_underexposed = false;  // even the longest leaves the background dark
};

// What a camera makes of a requested exposure: rounded to its resolution, clamped to its range.
double roundedExposureUs(double exposure_us, double step_us, double min_us, double max_us);

Result<BracketPlan> planBracket(double peak_dn_per_us, double background_dn_per_us,
                                double usable_range_dn, const BracketOptions& options = {});

}  // namespace glarecam::capture
