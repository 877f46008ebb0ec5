// Whether each frame of a merged stack agrees with the merge: the median, over a regular
// subsample of pixels where the frame is well exposed and the merge used at least two frames,
// of the frame's own luminance estimate divided by the merged luminance. Noise averages out of
// the median; what remains is a frame whose radiometry is wrong: files swapped in the manifest,
// a wrong exposure_us, gain or ND, a frame from another scene. Such a stack's luminance (and
// every ellipse) is wrong with no other symptom, so processStack warns and records the ratios.
#pragma once

#include <cstddef>
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
  double median_ratio = 0;  // NaN when the frame has too few well-exposed samples
  std::size_t samples = 0;
  bool agrees() const;  // within kMaxFrameDisagreement, or not judged
};

std::vector<FrameAgreement> frameAgreement(const MergeInput& input, const MergedImage& merged);

}  // namespace glarecam::calibration
