// What the illuminance tests share: the simulated pyrheliometer's config (docs/illuminance.md,
// "The simulated instrument").
#pragma once

#include "rig/illuminance/illuminance_config.h"

namespace glarecam::testing {

// The simulated head on loopback: float32 W/m² readings, 2 % stated uncertainty.
inline rig::IlluminanceConfig simulatedHeadConfig() {
  rig::IlluminanceConfig config;
  config.transport = rig::ModbusTransport::kSim;
  config.host = "127.0.0.1";
  config.data_type = rig::RegisterDataType::kFloat32;
  config.units = rig::IlluminanceUnits::kWattPerSquareMetre;
  config.uncertainty_pct = 2;
  return config;
}

}  // namespace glarecam::testing
