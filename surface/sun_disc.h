// The sun as the glare source sees it: a uniform disc of angular radius kSunHalfAngleDeg, and its
// weights on a square grid, which the BRDF route's picture and the simulated camera's surface
// scene convolve with (the truth, surface/lobe_contours.h, integrates over the disc instead).
#pragma once

#include <vector>

namespace glarecam::surface {

// The sun's angular radius: 4.65 mrad (docs/method.md "Why"; 0.53° full angle).
inline constexpr double kSunHalfAngleDeg = 0.2664;

// The disc's weights on a square grid of `pixel_deg` (odd side, centred): each pixel's share of
// the disc's area, from 16 × 16 points a pixel; they sum to 1. A radius of 0 is the single
// weight 1 (a point source).
std::vector<double> discKernel(double radius_deg, double pixel_deg, int& side);

}  // namespace glarecam::surface
