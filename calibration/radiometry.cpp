#include "calibration/radiometry.h"

#include <algorithm>
#include <cmath>

namespace glarecam::calibration {

bool isRepresentable(const FrameRadiometry& r) {
  const auto within = [](double value, double lo, double hi) {
    return std::isfinite(value) && value >= lo && value <= hi;
  };
  return within(r.scale_cd_m2_per_dn, kMinScaleCdM2PerDn, kMaxScaleCdM2PerDn) &&
         within(r.dn_per_electron, kMinDnPerElectron, kMaxDnPerElectron) &&
         within(r.read_noise_dn, 0.0, kMaxReadNoiseDn) && r.min_signal_dn > 0 &&
         within(r.min_signal_dn, 0.0, kMaxReadNoiseDn);
}

double linearGain(double gain_db) { return std::pow(10.0, gain_db / 20.0); }

NoiseModel noiseModelOf(const Calibration& calibration) {
  return calibration.noise.value_or(kAssumedNoiseModel);
}

FrameRadiometry frameRadiometry(const FrameSpec& frame, const Calibration& calibration) {
  const double gain = linearGain(frame.gain_db);
  const double reference_f = calibration.reference_f_number.value_or(1.0);
  const double aperture_ratio = frame.f_number.value_or(reference_f) / reference_f;
  const NoiseModel noise = noiseModelOf(calibration);
  FrameRadiometry radiometry;
  radiometry.scale_cd_m2_per_dn = calibration.luminance_factor /
                                  (frame.exposure_us * gain * frame.nd_transmission) *
                                  aperture_ratio * aperture_ratio;
  radiometry.dn_per_electron = noise.dn_per_electron * gain;
  radiometry.read_noise_dn = noise.read_noise_dn * gain;
  radiometry.min_signal_dn =
      std::max(kMinimumSignalDn, kDarkThresholdSigmas * radiometry.read_noise_dn);
  return radiometry;
}

std::vector<FrameRadiometry> frameRadiometry(const std::vector<FrameSpec>& frames,
                                             const Calibration& calibration) {
  std::vector<FrameRadiometry> result;
  result.reserve(frames.size());
  for (const FrameSpec& frame : frames) result.push_back(frameRadiometry(frame, calibration));
  return result;
}

}  // namespace glarecam::calibration
