// Whether each frame of a merged stack agrees with the merge: the median, over a regular
// subsample of pixels where the frame is well exposed and the merge used at least two frames,
// of the frame's own luminance estimate divided by the merged luminance. Noise averages out of
// the median; what remains is a frame whose radiometry is wrong: files swapped in the manifest,
// a wrong exposure_us, gain or ND, a frame from another scene. Such a stack's luminance (and
// every ellipse) is wrong with no other symptom, so processStack warns and records the ratios.
// Also: a sensor clipping below the calibration's saturation_dn (a wrong saturation_dn).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "calibration/hdr_merge.h"

namespace glarecam::calibration {

// The merge leans on the longest frames, so a wrong long frame shows mostly as the other frames
// reading off: a disagreement says the stack is wrong, not which frame (a leave-one-out
// reference would; not done yet).
// A frame's median ratio further than this from 1 is a radiometric error, not noise: the
// median over hundreds of pixels of ~1 % noise moves by far less, while the smallest real
// error (one bracket step swapped, a missing ND factor) is tens of percent.
inline constexpr double kMaxFrameDisagreement = 0.05;
// Fewer well-exposed samples than this judge nothing (NaN ratio).
inline constexpr std::size_t kMinAgreementSamples = 100;

struct FrameAgreement {
  double median_ratio = 0;  // NaN when the frame has too few well-exposed samples
  std::size_t samples = 0;
  bool agrees() const;  // within kMaxFrameDisagreement, or not judged
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
