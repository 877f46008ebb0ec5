// Opens the [illuminance] instrument a rig config names: the libmodbus backend for "rtu" and
// "tcp"; for "sim", first the simulated instrument (modbus_simulator.h) on loopback, then the same
// libmodbus backend over TCP to it. Without libmodbus in the build, kHardware saying so.
#pragma once

#include <memory>

#include "core/error.h"
#include "rig/illuminance/illuminance_config.h"
#include "rig/illuminance/illuminance_instrument.h"

namespace glarecam::rig {

class ModbusInstrumentSimulator;

struct OpenedIlluminance {
  // transport "sim": the simulated instrument being read (set its E and faults here); declared
  // first, so that it outlives the instrument reading it.
  std::unique_ptr<ModbusInstrumentSimulator> simulator;
  std::unique_ptr<IlluminanceInstrument> instrument;

  OpenedIlluminance();
  OpenedIlluminance(OpenedIlluminance&&) noexcept;
  OpenedIlluminance& operator=(OpenedIlluminance&&) noexcept;
  ~OpenedIlluminance();
};

// Whether this build reads Modbus instruments (GLARECAM_WITH_MODBUS).
bool modbusAvailable();

// A simulated instrument's E from now on (serves nothing else; a real instrument: nothing).
void setSimulatedIlluminance(OpenedIlluminance& opened, double illuminance_lx);

// `sim_illuminance_lx`: what a simulated instrument serves until told otherwise.
Result<OpenedIlluminance> openIlluminance(const IlluminanceConfig& config,
                                          double sim_illuminance_lx = 90'000);

}  // namespace glarecam::rig
