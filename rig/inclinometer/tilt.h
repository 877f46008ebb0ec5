// Tilt from an inclinometer's gravity vector. The sensor sits on the module frame with its z axis
// along the module's normal; its x and y axes lie in the module plane. Two signed axis tilts
// describe its attitude (tilt_x_deg: rotation about the sensor's x axis, atan2(y, z); tilt_y_deg:
// about y, atan2(-x, hypot(y, z))); the module tilt is the angle between the normal and the
// vertical, and moduleOrientation() adds the normal's azimuth from the configured facing.
//
// A reading averages N samples and rejects a moving rig (tilt scatter above a bound). The
// sensor's mounting error is removed by a zero offset measured with the flip method: two readings
// on the same surface, the frame turned 180° on it in between; the surface's tilt changes sign in
// the module's axes, the mounting error does not: the offset is the direction halfway between.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/error.h"
#include "rig/inclinometer/inclinometer.h"
#include "sun/incidence_angle.h"

namespace glarecam::rig {

struct AxisTilt {
  double x_deg = 0.0;
  double y_deg = 0.0;
};

// The sensor's mounting error as the axis tilts it reads on a level surface.
struct InclinometerZeroOffset {
  AxisTilt offset;
  double uncertainty_deg = 0.0;  // standard uncertainty of each axis's offset
  std::string measured_with;     // the sensor's URI, when recorded
};

// Samples per reading: two give a scatter; 100 000 take ≈ 2 h at the ADXL355's 15.6 Hz.
inline constexpr int kMinTiltSamples = 2;
inline constexpr int kMaxTiltSamples = 100000;

struct TiltOptions {
  int samples = 50;
  // ADXL355 noise at 15.6 Hz output data rate: 25 µg/√Hz × √(3.9 Hz × 1.6) ≈ 60 µg ≈ 0.004°
  // (datasheet, noise density and LPF bandwidth). Ten times that means the frame is moving (wind,
  // an operator) and the mean is not the tilt during the capture.
  double max_tilt_std_deg = 0.05;
  // A sample whose magnitude is off 1 g by more than this is not gravity alone: the rig is being
  // moved, or the range/scale is wrong. ADXL355 0 g offset ±75 mg + sensitivity ±2 % (datasheet).
  double gravity_tolerance_g = 0.15;
  Status validate() const;
};

struct TiltReading {
  AxisTilt tilt;                 // zero offset removed
  AxisTilt raw_tilt;             // as the sensor reads it
  double module_tilt_deg = 0.0;  // normal vs vertical, zero offset removed
  double tilt_std_deg =
      0.0;  // per-sample scatter in any one direction (RMS angle to the mean / √2)
  double tilt_uncertainty_deg = 0.0;  // standard uncertainty of module_tilt_deg (mean + offset)
  int samples = 0;
  AccelerationSample mean;  // raw mean vector, as recorded in a stack's geometry block
};

AxisTilt axisTilt(const AccelerationSample& sample);

// The module tilt of an (offset-corrected) attitude: acos(cos x · cos y).
double moduleTiltDeg(const AxisTilt& tilt);

// Removes the mounting error: rotates the sensor's gravity vector back by the offset.
AxisTilt correctedTilt(const AccelerationSample& sample, const InclinometerZeroOffset& zero);

// The inverse: the gravity vector (1 g) a sensor mounted with `mounting_offset` reads on a surface
// with the attitude `tilt`. What a simulator or a test feeds the maths above.
AccelerationSample mountedGravity(const AxisTilt& tilt, const AxisTilt& mounting_offset);

// The module's orientation (its normal's tilt and azimuth) from the sensor's corrected attitude
// and the module's facing azimuth. The facing azimuth is taken as 90° clockwise from the heading
// of the module's horizontal edge (the sensor's x axis): for a module that is not rolled sideways
// (tilt y = 0) it is simply the azimuth its normal points to; for a rolled one (a tracker turning
// about another axis, a frame out of true) the normal swings sideways and this finds where.
// Exact for any attitude but an x axis standing vertical, where the edge has no heading.
sun::ModuleOrientation moduleOrientation(const AxisTilt& tilt, double facing_azimuth_deg);

// Averages options.samples readings. Errors: a failing read (its error), a sample that is not
// gravity (magnitude), a moving rig (scatter above the bound), each naming the inclinometer.
// `on_sample` (optional) is called after each sample, for progress.
Result<TiltReading> measureTilt(Inclinometer& inclinometer, const TiltOptions& options,
                                const InclinometerZeroOffset& zero = {},
                                const std::function<void()>& on_sample = {});

// The flip method: `first` and `second` are raw readings with the frame turned 180° on the same
// surface in between. Uses the readings' mean vectors (exact at any surface tilt).
InclinometerZeroOffset flipZeroOffset(const TiltReading& first, const TiltReading& second);

}  // namespace glarecam::rig
