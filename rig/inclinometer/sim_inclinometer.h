// The `sim:` inclinometer: the real ADXL355 driver over the register-level simulator, the sensor
// lying on a surface with a given attitude and mounting error. What the demo, the simulated rig
// and the CLI tests measure tilt with.
#pragma once

#include <memory>
#include <string_view>

#include "core/error.h"
#include "rig/inclinometer/adxl355_simulator.h"
#include "rig/inclinometer/inclinometer.h"

namespace glarecam::rig {

// "30,roll_deg=1,offset_x_deg=0.3,noise_g=0.0001,seed=2,fault=saturated" (the part after
// "sim:") → the simulator's options. kBadInput naming the URI and the key.
Result<Adxl355SimulatorOptions> parseSimInclinometerId(std::string_view id);

Result<std::unique_ptr<Inclinometer>> openSimInclinometer(std::string_view id);

}  // namespace glarecam::rig
