// Inclinometer URIs, like the cameras': "scheme:id".
//   adxl355:/dev/i2c-1@0x1d   an ADXL355 on an i2c-dev bus (address 0x1d or 0x53; default 0x1d)
//   iio:iio:device0           a Linux IIO accelerometer through sysfs
//   sim:TILT_DEG[,key=value]  the register-level ADXL355 simulator on a surface tilted TILT_DEG
//                             about the sensor's x axis (keys: roll_deg, offset_x_deg,
//                             offset_y_deg, noise_g, seed, temperature_c, fault)
#pragma once

#include <memory>
#include <string_view>

#include "core/error.h"
#include "rig/inclinometer/inclinometer.h"

namespace glarecam::rig {

// Opens the inclinometer `uri` names. kBadInput for a malformed URI or unknown scheme (listing
// the known ones), kHardware when the device is absent or does not answer.
Result<std::unique_ptr<Inclinometer>> openInclinometer(std::string_view uri);

// Whether two URIs name the same device: equal, or both the simulator (whose URI describes the
// simulated surface, not a device).
bool sameInclinometer(std::string_view a, std::string_view b);

}  // namespace glarecam::rig
