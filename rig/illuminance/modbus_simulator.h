// A simulated Modbus illuminance instrument: a libmodbus TCP server on loopback (127.0.0.1, a
// free port the kernel picks) answering from a documented register map (docs/illuminance.md,
// "The simulated instrument"), on a thread of its own. The libmodbus backend reads it exactly as
// it reads a real instrument: in tests, in `glarecam doctor` and behind glarecamd --simulate.
//
// Register map (input and holding registers alike, 0-based protocol addresses; 32-bit values
// span two registers; the sun's direct normal irradiance I = E / efficacy_lm_w):
//
//   0–1   I, W/m², float32, high word first ("big")
//   2–3   I, W/m², float32, low word first ("little")
//   4     I, W/m² × 10, uint16 (scale 0.1)
//   5     I, W/m² × 10, int16 (scale 0.1)
//   6–7   I, mW/m², uint32, high word first (scale 0.001)
//   8–9   E, lx, float32, high word first
//   10    E, lx / 10, uint16 (scale 10)
//
// Other addresses get the exception ILLEGAL DATA ADDRESS; a request for another unit (slave id)
// is not answered (as a gateway without that unit would time out). Faults, settable at any time:
// dead (the port refuses connections), timeout (requests are read and never answered),
// exception (every request gets SERVER DEVICE FAILURE), out-of-range (serves 2000 W/m² and
// 200 klx), negative (serves −5 W/m² and −500 lx, a pyrheliometer's night offset).
#pragma once

#include <memory>

#include "core/error.h"
#include "rig/illuminance/illuminance_config.h"

namespace glarecam::rig {

struct ModbusSimulatorOptions {
  double illuminance_lx = 90'000;  // E served
  double efficacy_lm_w = kDefaultDirectEfficacyLmW;
  int slave_id = 1;
  SimulatedInstrumentFault fault = SimulatedInstrumentFault::kNone;
};

// The served registers for E and the efficacy (kSimulatorRegisterCount of them), as the map says.
inline constexpr int kSimulatorRegisterCount = 11;

class ModbusInstrumentSimulator {
 public:
  // Listens on 127.0.0.1 at a free port and serves until destroyed. kIo when it cannot listen.
  static Result<std::unique_ptr<ModbusInstrumentSimulator>> start(ModbusSimulatorOptions options);
  ~ModbusInstrumentSimulator();
  ModbusInstrumentSimulator(const ModbusInstrumentSimulator&) = delete;
  ModbusInstrumentSimulator& operator=(const ModbusInstrumentSimulator&) = delete;

  int port() const;
  // Thread-safe: the next request is answered with these.
  void setIlluminanceLx(double illuminance_lx);
  void setFault(SimulatedInstrumentFault fault);
  // Requests answered (with values or an exception) so far.
  int requestsAnswered() const;

  class Server;  // modbus_simulator.cpp: the libmodbus side

 private:
  explicit ModbusInstrumentSimulator(std::unique_ptr<Server> server);
  std::unique_ptr<Server> server_;
};

}  // namespace glarecam::rig
