// The luminance maximum of a merged image, found robustly. The plain pixel maximum is biased
// high by noise (on the flat top of a lobe it picks the largest of many noisy samples,
// typically +2 to +3 sigma) and a single hot pixel or spike would become "the maximum". So:
//  1. locate the peak on the second-largest value of each pixel's 3x3 neighbourhood: a lone
//     outlier never survives it, a real peak two pixels wide does (a 3x3 median would not);
//  2. fit a quadratic surface to ln L over a window around it, as large as the lobe's cap
//     allows along x and along y (a Gaussian-like lobe is quadratic in ln L near its top), and
//     take the vertex: the fit averages many pixels' noise instead of picking the largest.
// Falls back to the located value when the fit is not a proper cap. A top saturated in every
// frame gives a lower bound; an image under-exposed everywhere gives an upper bound.
#pragma once

#include <optional>
#include <string_view>

#include "calibration/hdr_merge.h"

namespace glarecam::pipeline {

enum class PeakMethod { kQuadraticFit, kNeighbourhood3x3, kLowerBound, kUpperBound };

struct LuminancePeak {
  double value_cd_m2 = 0;
  double x_px = 0, y_px = 0;  // sub-pixel position (pixel centres at integers)
  // Standard uncertainty of value_cd_m2 relative to it: from the fit's residuals, or the
  // located pixel's own uncertainty; NaN for bounds.
  double relative_uncertainty = 0;
  PeakMethod method = PeakMethod::kNeighbourhood3x3;
};

const char* toString(PeakMethod method);
// The method toString() names `text`, or nullopt.
std::optional<PeakMethod> peakMethodFromString(std::string_view text);

struct LocatedPeak {
  int x = 0, y = 0;
  float value = 0;
};

// Step 1 alone: the pixel with the largest second-largest value of its 3x3 neighbourhood (upper
// bounds ignored, outside the image counting as 0) and that value. Computed around the image's
// bright pixels only, not at all 5 million; exact all the same (ties may resolve differently).
LocatedPeak locateLuminancePeak(const calibration::MergedImage& merged);

// Reads the merged image's luminance, bound flags and relative uncertainty (for the
// uncertainty of a located, unfitted maximum).
LuminancePeak findLuminancePeak(const calibration::MergedImage& merged);

}  // namespace glarecam::pipeline
