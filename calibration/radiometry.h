// The radiometric model of one frame (docs/method.md, "Luminance image"):
//   L = K (DN - B) / (t g tau) (N / N_ref)^2 / F(x, y)
// FrameRadiometry folds everything but the flat field F into one scale (cd/m² per DN above
// black) and carries the frame's noise: shot noise from the conversion gain and read noise,
// both scaled by the analogue gain g (noise referred to the sensor, amplified with the signal).
#pragma once

#include <vector>

#include "core/stack_manifest.h"

namespace glarecam::calibration {

// Noise model assumed when a calibration has none: a typical 12-bit machine-vision sensor
// (about 2 e- read noise at 0.5 DN/e-). Results made with it say "noise_model": "assumed".
inline constexpr NoiseModel kAssumedNoiseModel{.read_noise_dn = 1.0, .dn_per_electron = 0.5};

// A frame pixel is "far enough above black" when its signal reaches this many read-noise
// standard deviations (a 3-sigma detection; below it the estimate is mostly noise).
inline constexpr double kDarkThresholdSigmas = 3.0;
// ...and never less than one DN, so a noiseless calibration still rejects black pixels.
inline constexpr double kMinimumSignalDn = 1.0;

struct FrameRadiometry {
  double scale_cd_m2_per_dn = 0;  // K / (t g tau) * (N / N_ref)^2
  double dn_per_electron = 0;     // conversion gain at this frame's analogue gain
  double read_noise_dn = 0;       // read noise at this frame's analogue gain
  double min_signal_dn = 0;       // DN above black below which the pixel is under-exposed
};

// The merge computes in float: its constants must stay well inside float's range once
// multiplied by a 16-bit DN and squared into variances. Values outside come from nonsense
// manifests (gain_db 1000, exposure_us 1e-30) and would give silently wrong luminance.
inline constexpr double kMinScaleCdM2PerDn = 1e-10, kMaxScaleCdM2PerDn = 1e10;
inline constexpr double kMinDnPerElectron = 1e-6, kMaxDnPerElectron = 1e6;
inline constexpr double kMaxReadNoiseDn = 1e6;
bool isRepresentable(const FrameRadiometry& radiometry);

double linearGain(double gain_db);
NoiseModel noiseModelOf(const Calibration& calibration);
FrameRadiometry frameRadiometry(const FrameSpec& frame, const Calibration& calibration);
std::vector<FrameRadiometry> frameRadiometry(const std::vector<FrameSpec>& frames,
                                             const Calibration& calibration);

}  // namespace glarecam::calibration
