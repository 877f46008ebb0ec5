// Sub-pixel iso-contour of one bright region of a float luminance image (marching squares).
//
// The region is the set of pixels at or above `level` that are 8-connected to a seed pixel,
// with its holes filled: a noise dip inside a glare spot neither splits it nor adds an inner
// contour, and a diagonal neck keeps a spot whole. The contour is that region's outer boundary,
// one closed loop of points ordered along it. Each point lies on the segment between a region
// pixel and a 4-neighbour outside it, where ln L crosses ln level, interpolated by the cubic
// through four pixels along that line: glare lobes are close to Gaussian, so ln L is close to
// quadratic, which the cubic reproduces exactly (linear interpolation is biased inward by up to
// 1/(8 r) px at contour radius r, 2 % on a 5 px FWHM; a binary mask by about half a pixel).
// Where the outer pixels are missing or the cubic is much flatter at the crossing than the chord
// between the two pixels (noise, or a contour grazing the pixel line: about 0.1 % of points on
// noise-free lobes), ln L is interpolated linearly between the two; L itself where the outside
// value is not positive. Non-finite pixels (NaN, inf) count as outside.
//
// Each point records its pixels and the derivatives of its position with respect to their
// values and to the level, so that pixel noise can be propagated into anything fitted to it.
// Pixel centres sit at integer coordinates, x right, y down (core/image.h). Pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/image.h"

namespace glarecam::pipeline {

struct PixelIndex {
  int x = 0, y = 0;
};

struct ContourPoint {
  double x_px = 0, y_px = 0;
  int step_x = 0, step_y = 0;  // unit step from the inside pixel toward the outside one
  // The pixels the crossing is interpolated from, along the step: the one behind the inside
  // pixel, the inside pixel, the outside pixel and the one beyond (row-major indices), with the
  // derivative of the crossing's distance along the step (px) with respect to each one's value
  // (0 for a slot not used), and with respect to the level (px per cd/m²).
  std::array<std::size_t, 4> pixels{};
  std::array<double, 4> dt_dvalue{};
  double dt_dlevel = 0;
  // The step leaves the image: the crossing is not observed (placed half a pixel out, drawn
  // but never fitted).
  bool on_border = false;
};

struct RegionContour {
  std::vector<ContourPoint> points;  // a closed loop (last point joins the first)
  std::size_t connected_pixels = 0;  // at or above the level, 8-connected to the seed
  std::size_t region_pixels = 0;     // the same after filling holes
  bool touches_border = false;
  bool touches_all_borders = false;  // left, top, right and bottom: the region fills the view
};

// The contour at `level` (> 0) of the region holding `seed`, or nothing when the seed pixel is
// below the level (or not finite). With `region_mask`, the region's pixels (before filling holes)
// are flagged 1 in it (made the image's size, all 0, first): for findRegions() to count the
// other regions without flooding this one again.
std::optional<RegionContour> traceRegionContour(const FloatImage& luminance, double level,
                                                PixelIndex seed, ByteImage* region_mask = nullptr);

// An 8-connected region at or above a level: its pixel box (inclusive) and pixel count.
struct RegionExtent {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::size_t pixels = 0;
};

// The 8-connected regions at or above `level` that have at least `min_pixels` pixels, in scan
// order. Every region at a higher level lies inside one of the regions at a lower level (or in
// one smaller than `min_pixels`, then itself smaller): what lets several levels share one scan.
// With `seen`, pixels flagged in it are left out (and the regions found flagged in it too).
std::vector<RegionExtent> findRegions(const FloatImage& luminance, double level,
                                      std::size_t min_pixels, ByteImage* seen = nullptr);

// How many 8-connected regions at or above `level` have at least `min_pixels` pixels.
int countRegions(const FloatImage& luminance, double level, std::size_t min_pixels);

}  // namespace glarecam::pipeline
