// Calibrated HDR merge: a bracketed stack of raw frames -> absolute luminance (cd/m²).
// Each frame pixel that is below saturation and at least min_signal_dn above black (the black
// level, or the dark frame pixel by pixel) gives an
// estimate L_i (radiometry.h). The estimates are combined with inverse-variance weights
// (Granados et al. 2010) from the noise model. Two passes per pixel: a pilot that judges each
// frame by its own reading, then the final sum in which a frame counts when the pilot predicts
// it within range (dark threshold .. saturation minus 3 sigma), so that no frame is truncated
// by its own noise, with weights at the pilot tapering smoothly to 0 toward that 3 sigma (from
// 12 sigma). Output per pixel: luminance, relative standard
// uncertainty (shot + read noise), the number of valid frames, and a bound flag for pixels
// valid in no frame (and for masked hot pixels): saturated everywhere gives a lower bound (the
// shortest frame's saturation luminance), dark everywhere an upper bound (the longest frame's
// detection threshold). Eight pixels at a time in registers, bands of rows on all cores, no
// per-pixel allocation.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "calibration/radiometry.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

enum class PixelBound : std::uint8_t {
  kMeasured = 0,    // at least one valid frame
  kLowerBound = 1,  // saturated in every frame: true luminance is at least the value
  kUpperBound = 2,  // under-exposed in every frame: true luminance is at most the value
  kMasked = 3,      // a hot pixel, masked out of the merge: the value is its neighbours' median
};

struct MergeInput {
  std::span<const RawFrame> frames;
  std::span<const FrameRadiometry> radiometry;  // one per frame
  double black_level_dn = 0;
  double saturation_dn = 0;                // values at or above are saturated
  const FloatImage* flat_field = nullptr;  // optional, 1 at the principal point
  std::span<const int> bit_depths =
      {};  // per frame, optional (16): an 8-bit frame saturates at 255
  // Optional: the per-pixel black (the calibration's dark frame) in place of black_level_dn, moved
  // to each frame's exposure by dark_offsets_dn[frame] (darkOffsetsDn). black_level_dn stays the
  // frame-wide level that saturation bounds are measured from.
  const FloatImage* dark_frame_dn = nullptr;
  std::span<const double> dark_offsets_dn = {};  // one per frame, with dark_frame_dn
  // Optional: pixels no frame may count (non-zero: the calibration's hot pixels). Each gets
  // PixelBound::kMasked, no valid frame, a NaN uncertainty, and the median of its unmasked
  // 8-neighbours (NaN when all of them are masked), so that contours run through it.
  const ByteImage* masked_pixels = nullptr;
};

struct MergeOptions {
  unsigned threads = 0;  // 0: all cores
};

struct MergedImage {
  FloatImage luminance_cd_m2;
  FloatImage relative_uncertainty;  // sigma / L; NaN where the pixel is a bound
  ByteImage valid_frames;
  ByteImage bound;  // PixelBound values
};

// A frame's saturation: the calibration's, unless the frame's container cannot hold it (an
// 8-bit frame saturates at 255 whatever the calibration of the sensor says).
double frameSaturationDn(const MergeInput& input, std::size_t frame);

// The black of one frame's pixel: the dark frame's value moved to the frame's exposure, or the
// black level.
double blackDn(const MergeInput& input, std::size_t frame, std::size_t pixel);

// The dark frame's offset at each frame's exposure: the sensor's mean dark current times the
// exposure's difference from the dark frame's (0 without a recorded dark-frame exposure).
std::vector<double> darkOffsetsDn(std::span<const FrameSpec> frames,
                                  const Calibration& calibration);

// Checks that the input is consistent (sizes, counts, finite constants).
Status validate(const MergeInput& input);

Result<MergedImage> merge(const MergeInput& input, const MergeOptions& options = {});
// Same, reusing `output`'s buffers when they already have the right size (benchmarks, daemon).
Status mergeInto(const MergeInput& input, const MergeOptions& options, MergedImage& output);

}  // namespace glarecam::calibration
