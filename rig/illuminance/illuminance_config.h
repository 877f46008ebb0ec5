// The rig's [illuminance] table (docs/illuminance.md): which Modbus instrument gives the source
// illuminance E, where its value is, and how it becomes lux. Read by readRigSections
// (rig_config.h); every key is checked, with "FILE:LINE: problem" errors.
//
// The register's value is decoded per `data_type` (16-bit registers are big-endian as Modbus
// defines them; a 32-bit value spans two registers, high word first for word_order "big"),
// multiplied by `scale`, and is then in `units`: lux as it is, or W/m² of direct normal
// irradiance turned into lux with the luminous efficacy of the direct beam K (lm/W):
//   E = K · I,   u(E)/E = √(u_instrument² + (u(K)/K)²).
//
// The efficacy of the direct beam is not a constant: measured values rise with the sun's
// elevation, from about 70 lm/W at 10° to 95–105 lm/W at 60° and above (Littlefair 1985, "The
// luminous efficacy of daylight: a review", Lighting Res. Technol. 17(4), 162–182: 70–105 lm/W;
// Littlefair 1988, "Measurements of the luminous efficacy of daylight", Lighting Res. Technol.
// 20(4), 177–188: ≈ 70 lm/W at 10°, ≈ 95 lm/W at 60°; above the atmosphere it is 133.8 klx /
// 1361 W/m² ≈ 98 lm/W, Darula, Kittler & Gueymard 2005). kDefaultDirectEfficacyLmW = 93 lm/W
// with a standard uncertainty of 8 lm/W is a round middle of those measurements for solar
// elevations above about 20°, not a model: below 20° the true efficacy is lower and a W/m²
// instrument overstates E (by up to a third at 10°). Give the rig's own value (efficacy_lm_w,
// efficacy_u_lm_w) when it is known, or use an instrument that reads lux.
#pragma once

#include <toml++/toml.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/error.h"

namespace glarecam::rig {

inline constexpr double kDefaultDirectEfficacyLmW = 93.0;
inline constexpr double kDefaultDirectEfficacyULmW = 8.0;

enum class ModbusTransport { kRtu, kTcp, kSim };
enum class RegisterType { kInput, kHolding };
enum class RegisterDataType { kUint16, kInt16, kUint32, kInt32, kFloat32 };
enum class WordOrder { kBig, kLittle };  // of a 32-bit value: high word first, or low word first
enum class IlluminanceUnits { kWattPerSquareMetre, kLux };

// The simulated instrument's fault (modbus_simulator.h), given in the config for tests and demos.
enum class SimulatedInstrumentFault { kNone, kDead, kTimeout, kException, kOutOfRange, kNegative };

struct IlluminanceConfig {
  ModbusTransport transport = ModbusTransport::kTcp;
  // RTU over RS-485.
  std::string device;  // "/dev/ttyUSB0"
  int baud = 9600;
  char parity = 'N';  // 'N', 'E', 'O'
  int data_bits = 8;
  int stop_bits = 1;
  // TCP (and, once served, the simulated instrument's loopback address).
  std::string host;
  int port = 502;
  int slave_id = 1;  // 1 … 247
  RegisterType register_type = RegisterType::kInput;
  int address = 0;  // the register's 0-based protocol address (PDU), 0 … 65535
  RegisterDataType data_type = RegisterDataType::kFloat32;
  WordOrder word_order = WordOrder::kBig;
  double scale = 1.0;  // value = decoded × scale, in `units`
  IlluminanceUnits units = IlluminanceUnits::kWattPerSquareMetre;
  double uncertainty_pct = 0;  // the instrument's relative standard uncertainty, %
  double efficacy_lm_w = kDefaultDirectEfficacyLmW;  // W/m² only
  double efficacy_u_lm_w = kDefaultDirectEfficacyULmW;
  std::chrono::milliseconds timeout{500};          // a reply's
  std::chrono::milliseconds sample_interval{100};  // between readings during a bracket
  std::string name = "pyrheliometer";              // what the instrument is, for the manifest
  SimulatedInstrumentFault sim_fault = SimulatedInstrumentFault::kNone;

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
  // How many 16-bit registers the value spans (1 or 2).
  int registerCount() const;
  // "modbus:/dev/ttyUSB0@1", "modbus:tcp:10.0.0.7:502@1", "modbus:sim:127.0.0.1:40123@1".
  std::string where() const;
  // "pyrheliometer modbus:/dev/ttyUSB0@1 (W/m², 93 lm/W)".
  std::string description() const;
};

// The [illuminance] table of `file` (kBadInput "FILE:LINE: problem" naming the key).
Result<IlluminanceConfig> readIlluminanceTable(const std::filesystem::path& file,
                                               const toml::table& table);

// The registers' value as `data_type` and `word_order` say (registers.size() ==
// registerCount()), times `scale`: in the config's units.
double decodeRegisters(const IlluminanceConfig& config, std::span<const std::uint16_t> registers);
// The inverse, for the simulator: `value` (in the config's units, before the scale) as registers.
void encodeRegisters(RegisterDataType data_type, WordOrder word_order, double value,
                     std::span<std::uint16_t> registers);

// The value in the config's units as lux; kHardware naming the instrument when it is not finite,
// not positive (no direct light, or a sensor fault) or above kMaxSourceIlluminanceLx.
Result<double> illuminanceLx(const IlluminanceConfig& config, double value);

std::string_view unitsText(IlluminanceUnits units);  // "W/m²", "lx"

}  // namespace glarecam::rig
