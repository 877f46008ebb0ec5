// A simulated machine-vision sensor: turns a true luminance image into the raw frame a linear
// camera would record at a given exposure, through the same radiometric model the merge
// inverts (calibration/radiometry.h), with Poisson shot noise, Gaussian read noise, a black
// level, and ADC quantisation and clipping at full scale. Deterministic for a seed.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

struct SensorModel {
  int adc_bits = 12;  // Mono12
  double black_level_dn = 64.0;
  double saturation_dn = 4000.0;  // declared linear limit, below the ADC's full scale
  double read_noise_dn = 2.0;
  double dn_per_electron = 0.5;
  double full_scale_dn() const { return static_cast<double>((1 << adc_bits) - 1); }
};

// The schema of truth.json, which every simulated scene and calibration target writes beside its
// stack (docs/simulate.md).
inline constexpr std::string_view kTruthSchema = "glarecam.truth/1";

// The simulated camera as every simulated scene sees it: frame size and noise seed, its sensor,
// its lens (field of view, distortion, f-number) and its luminance factor K (cd/m² per DN/µs at
// the f-number, without an ND filter). The glare scene's options (simulated_stack.h) and the
// calibration targets' (calibration_targets.h) both are one, so a camera passes between them
// whole.
struct SimulatedCameraModel {
  int width = 1224, height = 1024;  // half of a 5 MP machine-vision sensor
  std::uint64_t seed = 1;
  double horizontal_fov_deg = 40.0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3
  SensorModel sensor;
  double luminance_factor = 1500.0;  // K, cd/m² per DN/µs at f/8 without the ND filter
  double f_number = 8.0;
};

// Renders the frame `frame` of a stack calibrated by `calibration` (whose radiometry the sensor
// obeys exactly) looking at `luminance_cd_m2`.
RawFrame exposeFrame(const FloatImage& luminance_cd_m2, const FrameSpec& frame,
                     const Calibration& calibration, const SensorModel& sensor, std::uint64_t seed);

}  // namespace glarecam::capture
