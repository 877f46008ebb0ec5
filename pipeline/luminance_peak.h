// The luminance maximum of a merged image, found robustly. The plain pixel maximum is biased
// high by noise (on the flat top of a lobe it picks the largest of many noisy samples,
// typically +2 to +3 sigma) and a single hot pixel or spike would become "the maximum". So:
//  1. locate the peak on the 3x3 median of the image (a lone outlier never survives a median);
//  2. fit a quadratic surface to ln L over a window around it, as large as the lobe's cap
//     allows (a Gaussian-like lobe is quadratic in ln L near its top) and take the vertex: the
//     fit averages the noise of many pixels instead of picking the largest sample.
// Falls back to the median-filtered maximum when the fit is not a proper cap (too few
// measured pixels, vertex outside the window). A peak saturated in every frame is a lower bound.
#pragma once

#include "calibration/hdr_merge.h"

namespace glarecam::pipeline {

enum class PeakMethod { kQuadraticFit, kMedian3x3, kLowerBound };

struct LuminancePeak {
  double value_cd_m2 = 0;
  double x_px = 0, y_px = 0;  // sub-pixel position (pixel centres at integers)
  PeakMethod method = PeakMethod::kMedian3x3;
};

const char* toString(PeakMethod method);

LuminancePeak findLuminancePeak(const calibration::MergedImage& merged);

}  // namespace glarecam::pipeline
