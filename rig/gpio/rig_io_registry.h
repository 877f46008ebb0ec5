// Opens the rig's GPIO as the config names its chip: a real chip through libgpiod ("gpiochip0",
// "/dev/gpiochip0", a number or a label), or the simulator ("sim", or "sim:button_period_s=2":
// an operator pressing the button for 100 ms every 2 s), for the simulated rig and for trying
// `glarecam gpio` without hardware.
#pragma once

#include <memory>

#include "core/error.h"
#include "rig/gpio/rig_io.h"

namespace glarecam::rig {

Result<std::unique_ptr<RigIo>> openRigIo(const RigIoConfig& config);

}  // namespace glarecam::rig
