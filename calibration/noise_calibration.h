// `glarecam calibrate noise`: the photon transfer curve. Pairs of frames of a uniform source at
// several exposures give, per pair, the mean signal above black and the temporal variance
// var(a - b) / 2 (the fixed pattern and the flat field cancel in the difference). For a linear
// sensor var = read_noise² + dn_per_electron · mean; a weighted straight-line fit gives both,
// referred to 0 dB gain (docs/calibration.md). The merge weights frames with them.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "calibration/flat_calibration.h"
#include "calibration/frame_statistics.h"
#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// The fit needs pairs at this many exposures (a line through two points has no
// residual to judge it by).
inline constexpr std::size_t kMinTransferPoints = 3;

struct TransferPoint {
  double exposure_us = 0;
  double gain_db = 0;
  double mean_dn = 0;       // above black, at 0 dB
  double variance_dn2 = 0;  // temporal, at 0 dB
};

struct NoiseCalibration {
  NoiseModel model;            // at 0 dB
  double read_noise_u_dn = 0;  // standard uncertainties from the fit
  double dn_per_electron_u = 0;
  std::vector<TransferPoint> points;      // every pair used
  std::size_t pairs_near_saturation = 0;  // left out
};

Result<NoiseCalibration> calibrateNoise(std::span<const InputFrame> frames,
                                        const SensorLevels& levels, const Roi& roi);

nlohmann::json noiseValues(const NoiseCalibration& noise);

}  // namespace glarecam::calibration
