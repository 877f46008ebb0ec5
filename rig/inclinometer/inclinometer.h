// The rig's inclinometer: a 3-axis accelerometer on the module frame whose gravity vector gives
// the module's tilt. Backends: an ADXL355 over i2c-dev ("adxl355:/dev/i2c-1@0x1d"), a Linux IIO
// accelerometer through sysfs ("iio:iio:device0"), and a simulator ("sim:TILT_DEG"). Only the
// capture layer talks to one; the rest of the pipeline sees the tilt it yields (tilt.h).
#pragma once

#include <optional>
#include <string>

#include "core/error.h"

namespace glarecam::rig {

// One acceleration sample in the sensor's frame, in units of standard gravity (g). At rest the
// vector is gravity's reaction: +1 g along the axis pointing up.
struct AccelerationSample {
  double x_g = 0.0;
  double y_g = 0.0;
  double z_g = 0.0;
  std::optional<double> temperature_c;  // the sensor's die temperature, when it has one
};

struct InclinometerInfo {
  std::string uri;            // as opened: "adxl355:/dev/i2c-1@0x1d"
  std::string backend;        // "adxl355", "iio", "sim"
  std::string model;          // "ADXL355", the IIO device's name, ...
  std::string detail;         // range, output data rate, filter: for the log and the manifest
  double full_scale_g = 0.0;  // measuring range (±), 0 when the backend does not know it
};

class Inclinometer {
 public:
  virtual ~Inclinometer() = default;

  virtual const InclinometerInfo& info() const = 0;

  // The next fresh sample (a backend with a data-ready flag waits for it, bounded). Bad data is an
  // error naming the device: all axes zero, an axis at its full-scale code, a NaN or a read that
  // fails. kHardware for a device that is missing or stops answering.
  virtual Result<AccelerationSample> read() = 0;
};

}  // namespace glarecam::rig
