// A simulated machine-vision sensor: turns a true luminance image into the raw frame a linear
// camera would record at a given exposure, through the same radiometric model the merge
// inverts (calibration/radiometry.h), with Poisson shot noise, Gaussian read noise, a black
// level, and ADC quantisation and clipping at full scale. Deterministic for a seed.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

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
  // The sensor's own defects (fixed pattern, hot pixels) are drawn from this seed, not from the
  // noise seed: one sensor has the same defects in its dark frames and in its glare stacks.
  std::uint64_t sensor_seed = 1;
};

// A sensor's defects, the same in every frame it takes: each pixel's offset from the black level
// (the fixed pattern) and hot pixels, whose dark current adds rate × exposure.
// Above this a fixed pattern is no sensor's (a few DN on machine-vision sensors).
inline constexpr double kMaxFixedPatternDn = 100.0;

struct SensorDefects {
  double fixed_pattern_dn = 0;  // standard deviation of the per-pixel offset
  int hot_pixels = 0;
  bool any() const { return fixed_pattern_dn != 0 || hot_pixels != 0; }
};

// Dark current of the simulated hot pixels, DN per µs (20–60 DN/ms: a hot pixel of a warm CMOS
// sensor; a 10 ms dark frame shows it hundreds of DN above black).
inline constexpr double kHotRateMinDnPerUs = 0.020, kHotRateMaxDnPerUs = 0.060;

struct SensorDefectMap {
  FloatImage offset_dn;                         // fixed pattern
  FloatImage dark_current_dn_per_us;            // non-zero at hot pixels
  std::vector<std::pair<int, int>> hot_pixels;  // (x, y), sorted
};

// The defects of a width x height sensor with `sensor_seed`: the same for the same arguments.
SensorDefectMap sensorDefectMap(int width, int height, const SensorDefects& defects,
                                std::uint64_t sensor_seed);

// Renders the frame `frame` of a stack calibrated by `calibration` (whose radiometry the sensor
// obeys exactly) looking at `luminance_cd_m2`; with `defects`, each pixel's offset and dark current
// join the signal before the ADC quantises it (so a fixed pattern below 1 DN survives, as on a
// real sensor).
RawFrame exposeFrame(const FloatImage& luminance_cd_m2, const FrameSpec& frame,
                     const Calibration& calibration, const SensorModel& sensor, std::uint64_t seed,
                     const SensorDefectMap* defects = nullptr);

}  // namespace glarecam::capture
