// Summary statistics of a merged luminance image: the maximum and where it is, how much of
// the image was measured, and how many pixels are only bounds. Pure function, no I/O.
#pragma once

#include <cstddef>

#include "calibration/hdr_merge.h"
#include "pipeline/luminance_peak.h"

namespace glarecam::pipeline {

// Summaries over a whole image (median uncertainty, colour-scale percentiles) read a regular
// subsample of about this many pixels: exact enough, and independent of the image size.
inline constexpr std::size_t kSummarySamplePixels = 1 << 16;

inline std::size_t summarySampleStep(std::size_t pixel_count) {
  return pixel_count > kSummarySamplePixels ? pixel_count / kSummarySamplePixels : 1;
}

struct LuminanceStats {
  LuminancePeak max;                       // robust maximum (luminance_peak.h)
  double valid_fraction = 0;               // pixels with at least one valid frame
  std::size_t saturated_pixels = 0;        // saturated in every frame (lower bounds)
  std::size_t dark_pixels = 0;             // under-exposed in every frame (upper bounds)
  std::size_t masked_pixels = 0;           // the calibration's hot pixels
  double median_relative_uncertainty = 0;  // over measured pixels
};

LuminanceStats luminanceStats(const calibration::MergedImage& merged);

}  // namespace glarecam::pipeline
