#include "pipeline/luminance_stats.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace glarecam::pipeline {

LuminanceStats luminanceStats(const calibration::MergedImage& merged) {
  using calibration::PixelBound;
  LuminanceStats stats;
  const std::size_t count = merged.luminance_cd_m2.pixelCount();
  const std::uint8_t* bound = merged.bound.data();
  std::size_t measured = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const auto flag = static_cast<PixelBound>(bound[i]);
    measured += flag == PixelBound::kMeasured;
    stats.saturated_pixels += flag == PixelBound::kLowerBound;
    stats.dark_pixels += flag == PixelBound::kUpperBound;
    stats.masked_pixels += flag == PixelBound::kMasked;
  }
  if (count == 0) return stats;
  stats.max = findLuminancePeak(merged);
  stats.valid_fraction = static_cast<double>(measured) / static_cast<double>(count);

  std::vector<float> sample;
  const std::size_t step = summarySampleStep(count);
  const float* relative = merged.relative_uncertainty.data();
  for (std::size_t i = 0; i < count; i += step) {
    if (std::isfinite(relative[i])) sample.push_back(relative[i]);
  }
  if (!sample.empty()) {
    auto middle = sample.begin() + static_cast<std::ptrdiff_t>(sample.size() / 2);
    std::nth_element(sample.begin(), middle, sample.end());
    stats.median_relative_uncertainty = *middle;
  }
  return stats;
}

}  // namespace glarecam::pipeline
