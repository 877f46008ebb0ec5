// `glarecam calibrate flat`: frames of a uniform source (an integrating sphere's port, or a
// diffuser over the lens) give the flat field F(x, y): the per-pixel mean above black, each
// frame scaled to a common exposure, normalised to 1 at the principal point (the mean of a
// small window there, so that one pixel's noise does not scale the whole field). The merge
// divides by it (docs/stack-format.md).
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// Side of the window at the principal point the field is normalised over (121 pixels: the
// normalisation's own noise is a tenth of one pixel's).
inline constexpr int kFlatNormalisationWindowPx = 11;
// Frames whose mean signal is below this fraction of the usable range are too dark for a flat
// (shot noise would dominate the field).
inline constexpr double kMinFlatSignalFraction = 0.1;

struct SensorLevels {
  double black_level_dn = 0;
  double saturation_dn = 0;
};

struct FlatCalibration {
  FloatImage flat_field;  // 1 at the principal point
  double principal_x = 0, principal_y = 0;
  double min_value = 0, max_value = 0;  // of the field (vignetting: min < 1)
  std::size_t frames = 0;
  double mean_signal_dn = 0;  // above black, over the frames
};

// `principal` the point to normalise at (cx, cy of the intrinsics, or the image centre).
Result<FlatCalibration> calibrateFlat(std::span<const InputFrame> frames,
                                      const SensorLevels& levels, double principal_x,
                                      double principal_y);

nlohmann::json flatValues(const FlatCalibration& flat, const std::string& flat_file);

}  // namespace glarecam::calibration
