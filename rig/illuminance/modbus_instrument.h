// The libmodbus backend of the illuminance instrument (illuminance_instrument.h): RTU over a
// serial line (RS-485 adapters that switch direction themselves, as USB ones do) or TCP. Built
// when libmodbus is (GLARECAM_WITH_MODBUS); only modbus_instrument.cpp includes <modbus.h>.
//
// Each read() is one request for the configured register(s), answered within `timeout`. A
// connection refused, lost or timed out is closed and opened again at the next read(); an
// exception reply names the exception. Every failure is kHardware naming the instrument
// (config.where()).
#pragma once

#include <memory>

#include "core/error.h"
#include "rig/illuminance/illuminance_config.h"
#include "rig/illuminance/illuminance_instrument.h"

namespace glarecam::rig {

// The instrument, connected at its first read() (so that one absent now is tried again at each
// read): kBadInput for an invalid config.
Result<std::unique_ptr<IlluminanceInstrument>> openModbusInstrument(
    const IlluminanceConfig& config);

}  // namespace glarecam::rig
