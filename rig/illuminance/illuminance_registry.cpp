#include "rig/illuminance/illuminance_registry.h"

#include "core/build_config.h"
#if GLARECAM_WITH_MODBUS
#include "rig/illuminance/modbus_instrument.h"
#include "rig/illuminance/modbus_simulator.h"
#endif

namespace glarecam::rig {

#if GLARECAM_WITH_MODBUS
OpenedIlluminance::OpenedIlluminance() = default;
OpenedIlluminance::OpenedIlluminance(OpenedIlluminance&&) noexcept = default;
OpenedIlluminance& OpenedIlluminance::operator=(OpenedIlluminance&&) noexcept = default;
OpenedIlluminance::~OpenedIlluminance() = default;

bool modbusAvailable() { return true; }

void setSimulatedIlluminance(OpenedIlluminance& opened, double illuminance_lx) {
  if (opened.simulator) opened.simulator->setIlluminanceLx(illuminance_lx);
}

Result<OpenedIlluminance> openIlluminance(const IlluminanceConfig& config,
                                          double sim_illuminance_lx) {
  GLARECAM_CHECK(config.validate());
  OpenedIlluminance opened;
  IlluminanceConfig reading = config;
  if (config.transport == ModbusTransport::kSim) {
    GLARECAM_ASSIGN(opened.simulator,
                    ModbusInstrumentSimulator::start({.illuminance_lx = sim_illuminance_lx,
                                                      .efficacy_lm_w = config.efficacy_lm_w,
                                                      .slave_id = config.slave_id,
                                                      .fault = config.sim_fault}));
    reading.host = "127.0.0.1";
    reading.port = opened.simulator->port();
  }
  GLARECAM_ASSIGN(opened.instrument, openModbusInstrument(reading));
  return opened;
}
#else
// Without libmodbus the simulator is an incomplete type: nothing ever holds one.
class ModbusInstrumentSimulator {};
OpenedIlluminance::OpenedIlluminance() = default;
OpenedIlluminance::OpenedIlluminance(OpenedIlluminance&&) noexcept = default;
OpenedIlluminance& OpenedIlluminance::operator=(OpenedIlluminance&&) noexcept = default;
OpenedIlluminance::~OpenedIlluminance() = default;

bool modbusAvailable() { return false; }

void setSimulatedIlluminance(OpenedIlluminance&, double) {}

Result<OpenedIlluminance> openIlluminance(const IlluminanceConfig& config, double) {
  GLARECAM_CHECK(config.validate());
  return hardwareError(config.where() +
                       ": this glarecam was built without libmodbus (install libmodbus-dev and "
                       "build again): the [illuminance] instrument cannot be read");
}
#endif

}  // namespace glarecam::rig
