// Whether the frames of a merged stack agree with each other. Exposure-adjacent frames are
// compared where the merge predicts both well exposed: the median ratio of their estimates
// links them, a chain of links gives each frame's scale relative to the rest, and anchoring on
// the median frame makes a single wrong frame read its own error while the others read 1 (two
// frames alone cannot tell which is right: both read half the disagreement). Noise averages out
// of the medians; what remains is wrong radiometry: files swapped in the manifest, a wrong
// exposure_us, gain or ND, a frame from another scene. Such a stack's luminance (and every
// ellipse) is wrong with no other symptom, so processStack warns and records the ratios.
// Also: a sensor clipping below the calibration's saturation_dn (a wrong saturation_dn).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "calibration/hdr_merge.h"

namespace glarecam::calibration {

// A frame's median ratio further than this from 1 is a radiometric error, not noise: the
// median over hundreds of pixels of ~1 % noise moves by far less, while the smallest real
// error (one bracket step swapped, a missing ND factor) is tens of percent.
inline constexpr double kMaxFrameDisagreement = 0.05;
// Fewer well-exposed samples than this judge nothing (NaN ratio).
inline constexpr std::size_t kMinAgreementSamples = 100;

struct FrameAgreement {
  double median_ratio = 0;  // NaN when the frame is linked to no other (too few samples)
  std::size_t samples = 0;  // pixel pairs in its links
  bool agrees() const;      // within kMaxFrameDisagreement, or not judged
};

std::vector<FrameAgreement> frameAgreement(const MergeInput& input, const MergedImage& merged);

// A sensor that clips below the calibration's saturation_dn piles its brightest pixels up on
// one value: the frame's maximum, below saturation, held by at least kMinClippedShare of its
// pixels (and kMinClippedPixels). The merge would take those clipped readings as valid.
inline constexpr double kMinClippedShare = 1e-3;
inline constexpr std::size_t kMinClippedPixels = 50;
// ...at a value at least this many dark thresholds above black (a black frame piles up on
// black), held at least this many times as often as the value just below it (a spike, not a
// flat field's top).
inline constexpr double kMinClippingSignal = 20;
inline constexpr std::size_t kMinSpikeFactor = 4;

struct ClippingBelowSaturation {
  std::size_t frame = 0;
  double dn = 0;  // the value the pixels pile up on
  std::size_t pixels = 0;
};

// The first such frame, if any.
std::optional<ClippingBelowSaturation> clippingBelowSaturation(const MergeInput& input);

}  // namespace glarecam::calibration
