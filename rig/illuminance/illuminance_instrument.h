// The rig's illuminance instrument: a smart pyrheliometer (direct normal irradiance, W/m²) or an
// illuminance head (lx) aimed at the sun, read over Modbus (RTU over RS-485, or TCP). It gives the
// source illuminance E of each stack (docs/method.md "Reference illuminance", origin `sensor`).
// Backends: libmodbus (modbus_instrument.cpp, the only file that includes <modbus.h>), which also
// reads the simulated instrument (modbus_simulator.h) over loopback TCP. The sampler
// (illuminance_sampler.h) reads one repeatedly during a bracket.
//
// A reading is already in lux (a W/m² value converted with the configured luminous efficacy of
// the direct beam, illuminance_config.h) and already checked: not finite, zero or negative (no
// direct light, a sensor fault) or above kMaxSourceIlluminanceLx (a unit mistake) is an error,
// never a number.
#pragma once

#include <chrono>
#include <string>

#include "core/error.h"

namespace glarecam::rig {

struct IlluminanceReading {
  double illuminance_lx = 0;  // E, direct normal
  double raw_value = 0;       // as the instrument gave it, after `scale`, in its units
  // When the request was sent (steady clock): a reading is as old as the question that got it.
  std::chrono::steady_clock::time_point requested_at{};
};

struct IlluminanceInstrumentInfo {
  // "pyrheliometer modbus:tcp:127.0.0.1:1502@1 (W/m², 93 lm/W)": the manifest's `instrument`.
  std::string description;
  // Relative standard uncertainties of one reading (fractions): the instrument's own, stated by
  // its calibration certificate, and the efficacy's (0 for an instrument that reads lx).
  double instrument_u_rel = 0;
  double efficacy_u_rel = 0;
};

class IlluminanceInstrument {
 public:
  virtual ~IlluminanceInstrument() = default;
  virtual const IlluminanceInstrumentInfo& info() const = 0;
  // One reading now. kHardware naming the instrument for a connection refused or lost, a
  // timeout, a Modbus exception reply, or a value out of range.
  virtual Result<IlluminanceReading> read() = 0;
};

}  // namespace glarecam::rig
