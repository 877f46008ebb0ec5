#include "calibration/frame_consistency.h"

#include <algorithm>
#include <cmath>

namespace glarecam::calibration {
namespace {

// About this many pixels are sampled, on a regular grid: enough for a stable median.
constexpr std::size_t kSamplePixels = 1 << 16;
// "Well exposed": predicted far above the dark threshold (where the merge truncates readings)
// and below this fraction of the range to saturation.
constexpr double kDarkMarginFactor = 10.0;
constexpr double kSaturationMarginFraction = 0.9;

std::vector<std::size_t> gridSamples(int width, int height, int stride) {
  std::vector<std::size_t> samples;
  for (int y = stride / 2; y < height; y += stride)
    for (int x = stride / 2; x < width; x += stride)
      samples.push_back(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(x));
  return samples;
}

}  // namespace

bool FrameAgreement::agrees() const {
  return !std::isfinite(median_ratio) || std::abs(median_ratio - 1.0) <= kMaxFrameDisagreement;
}

std::vector<FrameAgreement> frameAgreement(const MergeInput& input, const MergedImage& merged) {
  const int width = merged.luminance_cd_m2.width(), height = merged.luminance_cd_m2.height();
  // A regular grid of rows and columns (one stride along a row would alias with the width).
  const int stride = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(width) * height /
                                                            static_cast<double>(kSamplePixels))));
  std::vector<FrameAgreement> result;
  for (std::size_t f = 0; f < input.frames.size(); ++f) {
    const FrameRadiometry& r = input.radiometry[f];
    const double low_dn = input.black_level_dn + kDarkMarginFactor * r.min_signal_dn;
    const double high_dn =
        input.black_level_dn +
        kSaturationMarginFraction * (frameSaturationDn(input, f) - input.black_level_dn);
    std::vector<double> ratios;
    for (std::size_t i : gridSamples(width, height, stride)) {
      const double merged_cd_m2 = merged.luminance_cd_m2.data()[i];
      if (merged.valid_frames.data()[i] < 2 || !(merged_cd_m2 > 0)) continue;
      const double flat = input.flat_field ? input.flat_field->data()[i] : 1.0;
      // Pixels chosen by what the merge predicts for this frame, not by the frame's own
      // reading: choosing by the reading keeps the readings noise pushed up near the bound.
      const double predicted_dn = input.black_level_dn + merged_cd_m2 * flat / r.scale_cd_m2_per_dn;
      if (!(predicted_dn >= low_dn && predicted_dn <= high_dn)) continue;
      const double dn = input.frames[f].data()[i];
      ratios.push_back(r.scale_cd_m2_per_dn * (dn - input.black_level_dn) / flat / merged_cd_m2);
    }
    FrameAgreement agreement{std::nan(""), ratios.size()};
    if (ratios.size() >= kMinAgreementSamples) {
      auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
      std::nth_element(ratios.begin(), middle, ratios.end());
      agreement.median_ratio = *middle;
    }
    result.push_back(agreement);
  }
  return result;
}

std::optional<ClippingBelowSaturation> clippingBelowSaturation(const MergeInput& input) {
  for (std::size_t f = 0; f < input.frames.size(); ++f) {
    const RawFrame& frame = input.frames[f];
    const std::uint16_t* begin = frame.data();
    const std::uint16_t* end = begin + frame.pixelCount();
    const std::uint16_t top = begin == end ? 0 : *std::max_element(begin, end);
    // Only a bright value can be a clipping level (a black frame piles up on black), and only
    // a spike is one (a flat field's brightest values are many, but so are the next ones).
    const double black = input.black_level_dn, saturation = frameSaturationDn(input, f);
    const double bright = black + kMinClippingSignal * input.radiometry[f].min_signal_dn;
    if (!(top < saturation) || top < bright) continue;
    const auto pixels = static_cast<std::size_t>(std::count(begin, end, top));
    const auto below = static_cast<std::size_t>(std::count(begin, end, top - 1));
    const auto share = static_cast<double>(pixels) / static_cast<double>(frame.pixelCount());
    if (pixels >= kMinClippedPixels && share >= kMinClippedShare &&
        pixels >= kMinSpikeFactor * below)
      return {{f, double(top), pixels}};
  }
  return std::nullopt;
}

}  // namespace glarecam::calibration
