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

namespace {

// One sampled pixel as every frame sees it: its estimate, and whether the merge predicts it
// well exposed there.
struct FrameView {
  double estimate_cd_m2 = 0;
  bool in_range = false;
};

// Fills `views` (one per frame, reused across pixels: no allocation per sample).
void frameViews(const MergeInput& input, std::size_t pixel, double merged_cd_m2,
                std::vector<FrameView>& views) {
  const double flat = input.flat_field ? input.flat_field->data()[pixel] : 1.0;
  views.resize(input.frames.size());
  for (std::size_t f = 0; f < input.frames.size(); ++f) {
    const FrameRadiometry& r = input.radiometry[f];
    const double black = blackDn(input, f, pixel);
    // Chosen by what the merge predicts for this frame, not by the frame's own reading:
    // choosing by the reading keeps the readings noise pushed up near the bound.
    const double predicted_dn = black + merged_cd_m2 * flat / r.scale_cd_m2_per_dn;
    const double low_dn = black + kDarkMarginFactor * r.min_signal_dn;
    const double high_dn =
        black + kSaturationMarginFraction * (frameSaturationDn(input, f) - black);
    views[f] = {r.scale_cd_m2_per_dn * (input.frames[f].data()[pixel] - black) / flat,
                predicted_dn >= low_dn && predicted_dn <= high_dn && flat > 0};
  }
}

}  // namespace

namespace {

// The median; for an even count the mean of the two middle values (two frames that disagree
// are then both off by half the disagreement: neither can be told to be the right one).
double median(std::vector<double> values) {
  const auto half = static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), values.begin() + half, values.end());
  const double upper = values[static_cast<std::size_t>(half)];
  if (values.size() % 2 == 1) return upper;
  return (upper + *std::max_element(values.begin(), values.begin() + half)) / 2;
}

// Frames from the shortest effective exposure (largest scale) to the longest.
std::vector<std::size_t> exposureOrder(const MergeInput& input) {
  std::vector<std::size_t> order(input.frames.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return input.radiometry[a].scale_cd_m2_per_dn > input.radiometry[b].scale_cd_m2_per_dn;
  });
  return order;
}

// Frames linked by measured ratios, each with its log offset along the chain; anchored on the
// segment's median so that one wrong frame stands out and the consensus reads 1.
void anchorSegment(const std::vector<std::size_t>& frames, const std::vector<double>& offset,
                   std::vector<FrameAgreement>& result) {
  if (frames.size() < 2) return;  // a frame linked to no other: not checked
  std::vector<double> offsets;
  for (const std::size_t f : frames) offsets.push_back(offset[f]);
  const double anchor = median(offsets);
  for (const std::size_t f : frames) result[f].median_ratio = std::exp(offset[f] - anchor);
}

}  // namespace

std::vector<FrameAgreement> frameAgreement(const MergeInput& input, const MergedImage& merged) {
  const int width = merged.luminance_cd_m2.width(), height = merged.luminance_cd_m2.height();
  // A regular grid of rows and columns (one stride along a row would alias with the width).
  const int stride = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(width) * height /
                                                            static_cast<double>(kSamplePixels))));
  // Frames are compared in exposure-adjacent pairs, at pixels where the merge predicts both
  // well exposed: each pair's median ratio of estimates links the two. A chain of links gives
  // every frame's scale relative to the others; anchored on their median, a single wrong frame
  // reads its own error and the rest read 1. (Compared with the merge itself, a wrong long frame
  // would make the others look wrong: the merge leans on it.)
  const std::vector<std::size_t> order = exposureOrder(input);
  const std::size_t links = order.empty() ? 0 : order.size() - 1;
  std::vector<std::vector<double>> link_ratios(links);
  std::vector<FrameView> views;
  for (std::size_t i : gridSamples(width, height, stride)) {
    const double merged_cd_m2 = merged.luminance_cd_m2.data()[i];
    if (merged.valid_frames.data()[i] < 2 || !(merged_cd_m2 > 0)) continue;
    frameViews(input, i, merged_cd_m2, views);
    for (std::size_t l = 0; l < links; ++l) {
      const FrameView &a = views[order[l]], &b = views[order[l + 1]];
      if (a.in_range && b.in_range && b.estimate_cd_m2 > 0)
        link_ratios[l].push_back(a.estimate_cd_m2 / b.estimate_cd_m2);
    }
  }
  std::vector<FrameAgreement> result(input.frames.size(), FrameAgreement{std::nan(""), 0});
  std::vector<double> offset(input.frames.size(), 0.0);
  std::vector<std::size_t> segment;
  for (std::size_t l = 0; l <= links && !order.empty(); ++l) {
    const std::size_t f = order[l];
    if (segment.empty()) segment.push_back(f);
    if (l == links) break;
    const std::size_t next = order[l + 1];
    const bool linked = link_ratios[l].size() >= kMinAgreementSamples;
    if (linked) {
      const double ratio = median(link_ratios[l]);  // L_f / L_next = exp(offset_f - offset_next)
      offset[next] = offset[f] - std::log(ratio);
      result[f].samples += link_ratios[l].size();
      result[next].samples += link_ratios[l].size();
    } else {
      anchorSegment(segment, offset, result);
      segment.clear();
      offset[next] = 0.0;
    }
    segment.push_back(next);
  }
  anchorSegment(segment, offset, result);
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
