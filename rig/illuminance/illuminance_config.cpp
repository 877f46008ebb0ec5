#include "rig/illuminance/illuminance_config.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "core/source_illuminance.h"
#include "core/config_table.h"

namespace glarecam::rig {

namespace {

constexpr std::int64_t kMaxIlluminanceTimeoutMs = 10'000;
constexpr std::int64_t kMaxSampleIntervalMs = 60'000;

template <typename Enum>
Enum illuminanceChoice(std::string_view word,
                       std::initializer_list<std::pair<std::string_view, Enum>> words) {
  for (const auto& [text, value] : words)
    if (text == word) return value;
  return words.begin()->second;
}

}  // namespace

std::string_view unitsText(IlluminanceUnits units) {
  return units == IlluminanceUnits::kLux ? "lx" : "W/m²";
}

int IlluminanceConfig::registerCount() const {
  return data_type == RegisterDataType::kUint16 || data_type == RegisterDataType::kInt16 ? 1 : 2;
}

std::string IlluminanceConfig::where() const {
  switch (transport) {
    case ModbusTransport::kRtu:
      return fmt::format("modbus:{}@{}", device, slave_id);
    case ModbusTransport::kTcp:
      return fmt::format("modbus:tcp:{}:{}@{}", host, port, slave_id);
    case ModbusTransport::kSim:
      break;
  }
  return fmt::format("modbus:sim:{}:{}@{}", host, port, slave_id);
}

std::string IlluminanceConfig::description() const {
  if (units == IlluminanceUnits::kLux) return fmt::format("{} {} (lx)", name, where());
  return fmt::format("{} {} (W/m², {:g} lm/W)", name, where(), efficacy_lm_w);
}

Status IlluminanceConfig::validate() const {
  if (transport == ModbusTransport::kRtu && device.empty())
    return badInput("[illuminance] transport \"rtu\" needs device = \"/dev/ttyUSB0\"");
  if (transport == ModbusTransport::kTcp && host.empty())
    return badInput("[illuminance] transport \"tcp\" needs host = \"ADDRESS\"");
  if (!(slave_id >= 1 && slave_id <= 247))
    return badInput(fmt::format("[illuminance] slave_id {} is outside [1, 247]", slave_id));
  if (address < 0 || address + registerCount() - 1 > 65535)
    return badInput(fmt::format("[illuminance] address {} is outside [0, 65535]", address));
  if (!std::isfinite(scale) || scale == 0)
    return badInput("[illuminance] scale must be finite and not zero");
  if (!(uncertainty_pct > 0 && uncertainty_pct < 50))
    return badInput("[illuminance] uncertainty_pct must be in (0, 50) %");
  if (units == IlluminanceUnits::kWattPerSquareMetre &&
      !(efficacy_lm_w >= 50 && efficacy_lm_w <= 150 && efficacy_u_lm_w >= 0 &&
        efficacy_u_lm_w < efficacy_lm_w))
    return badInput(
        "[illuminance] efficacy_lm_w must be in [50, 150] lm/W, its uncertainty below it");
  if (timeout.count() <= 0 || sample_interval.count() <= 0)
    return badInput("[illuminance] timeout_ms and sample_interval_ms must be positive");
  if (sim_fault != SimulatedInstrumentFault::kNone && transport != ModbusTransport::kSim)
    return badInput("[illuminance] sim_fault is for transport = \"sim\" only");
  return {};
}

Result<IlluminanceConfig> readIlluminanceTable(const std::filesystem::path& file,
                                               const toml::table& table) {
  TableReader reader(file, table, "illuminance");
  IlluminanceConfig config;
  std::optional<std::string> word;
  GLARECAM_ASSIGN(word, reader.choice("transport", {"rtu", "tcp", "sim"}));
  if (!word) return reader.tableError("transport is missing (\"rtu\", \"tcp\" or \"sim\")");
  config.transport = illuminanceChoice<ModbusTransport>(*word, {{"rtu", ModbusTransport::kRtu},
                                                                {"tcp", ModbusTransport::kTcp},
                                                                {"sim", ModbusTransport::kSim}});
  std::optional<std::string> text;
  GLARECAM_ASSIGN(text, reader.string("device"));
  if (text) config.device = *text;
  GLARECAM_ASSIGN(text, reader.string("host"));
  if (text) config.host = *text;
  std::optional<std::int64_t> integer;
  GLARECAM_ASSIGN(integer, reader.integer("baud", 300, 4'000'000));
  if (integer) config.baud = static_cast<int>(*integer);
  GLARECAM_ASSIGN(word, reader.choice("parity", {"none", "even", "odd"}));
  if (word) config.parity = static_cast<char>(std::toupper((*word)[0]));
  GLARECAM_ASSIGN(integer, reader.integer("data_bits", 5, 8));
  if (integer) config.data_bits = static_cast<int>(*integer);
  GLARECAM_ASSIGN(integer, reader.integer("stop_bits", 1, 2));
  if (integer) config.stop_bits = static_cast<int>(*integer);
  GLARECAM_ASSIGN(integer, reader.integer("port", 1, 65535));
  if (integer) config.port = static_cast<int>(*integer);
  GLARECAM_ASSIGN(integer, reader.integer("slave_id", 1, 247));
  if (integer) config.slave_id = static_cast<int>(*integer);
  GLARECAM_ASSIGN(word, reader.choice("register_type", {"input", "holding"}));
  if (word) config.register_type = *word == "input" ? RegisterType::kInput : RegisterType::kHolding;
  GLARECAM_ASSIGN(integer, reader.integer("address", 0, 65535));
  if (integer) config.address = static_cast<int>(*integer);
  GLARECAM_ASSIGN(word,
                  reader.choice("data_type", {"uint16", "int16", "uint32", "int32", "float32"}));
  if (!word)
    return reader.tableError("data_type is missing (uint16, int16, uint32, int32, float32)");
  config.data_type =
      illuminanceChoice<RegisterDataType>(*word, {{"uint16", RegisterDataType::kUint16},
                                                  {"int16", RegisterDataType::kInt16},
                                                  {"uint32", RegisterDataType::kUint32},
                                                  {"int32", RegisterDataType::kInt32},
                                                  {"float32", RegisterDataType::kFloat32}});
  GLARECAM_ASSIGN(word, reader.choice("word_order", {"big", "little"}));
  if (word) config.word_order = *word == "big" ? WordOrder::kBig : WordOrder::kLittle;
  std::optional<double> number;
  GLARECAM_ASSIGN(number, reader.number("scale", -1e9, 1e9));
  if (number) config.scale = *number;
  GLARECAM_ASSIGN(word, reader.choice("units", {"W/m2", "lx"}));
  if (!word) return reader.tableError("units is missing (\"W/m2\" or \"lx\")");
  config.units = *word == "lx" ? IlluminanceUnits::kLux : IlluminanceUnits::kWattPerSquareMetre;
  GLARECAM_ASSIGN(config.uncertainty_pct, reader.requiredNumber("uncertainty_pct", 0.01, 49.9));
  const toml::node* efficacy = table.get("efficacy_lm_w");
  const toml::node* efficacy_u = table.get("efficacy_u_lm_w");
  GLARECAM_ASSIGN(number, reader.number("efficacy_lm_w", 50, 150));
  if (number) config.efficacy_lm_w = *number;
  GLARECAM_ASSIGN(number, reader.number("efficacy_u_lm_w", 0, 50));
  if (number) config.efficacy_u_lm_w = *number;
  if (config.units == IlluminanceUnits::kLux && (efficacy || efficacy_u))
    return reader.error(
        efficacy ? *efficacy : *efficacy_u,
        "illuminance.efficacy_lm_w is for units = \"W/m2\"; this instrument reads lx");
  GLARECAM_ASSIGN(integer, reader.integer("timeout_ms", 1, kMaxIlluminanceTimeoutMs));
  if (integer) config.timeout = std::chrono::milliseconds(*integer);
  GLARECAM_ASSIGN(integer, reader.integer("sample_interval_ms", 1, kMaxSampleIntervalMs));
  if (integer) config.sample_interval = std::chrono::milliseconds(*integer);
  GLARECAM_ASSIGN(text, reader.string("name"));
  if (text) config.name = *text;
  GLARECAM_ASSIGN(word, reader.choice("sim_fault", {"none", "dead", "timeout", "exception",
                                                    "out-of-range", "negative"}));
  if (word)
    config.sim_fault = illuminanceChoice<SimulatedInstrumentFault>(
        *word, {{"none", SimulatedInstrumentFault::kNone},
                {"dead", SimulatedInstrumentFault::kDead},
                {"timeout", SimulatedInstrumentFault::kTimeout},
                {"exception", SimulatedInstrumentFault::kException},
                {"out-of-range", SimulatedInstrumentFault::kOutOfRange},
                {"negative", SimulatedInstrumentFault::kNegative}});
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (config.transport == ModbusTransport::kSim && config.host.empty()) config.host = "127.0.0.1";
  const Status valid = config.validate();
  if (!valid) return reader.tableError(valid.error().message);
  return config;
}

double decodeRegisters(const IlluminanceConfig& config, std::span<const std::uint16_t> registers) {
  double value = 0;
  if (config.registerCount() == 1) {
    value = config.data_type == RegisterDataType::kInt16
                ? static_cast<double>(static_cast<std::int16_t>(registers[0]))
                : static_cast<double>(registers[0]);
  } else {
    const bool big = config.word_order == WordOrder::kBig;
    const std::uint32_t bits =
        (std::uint32_t{registers[big ? 0 : 1]} << 16) | std::uint32_t{registers[big ? 1 : 0]};
    switch (config.data_type) {
      case RegisterDataType::kUint32:
        value = static_cast<double>(bits);
        break;
      case RegisterDataType::kInt32:
        value = static_cast<double>(static_cast<std::int32_t>(bits));
        break;
      default:
        value = static_cast<double>(std::bit_cast<float>(bits));
        break;
    }
  }
  return value * config.scale;
}

void encodeRegisters(RegisterDataType data_type, WordOrder word_order, double value,
                     std::span<std::uint16_t> registers) {
  std::uint32_t bits = 0;
  switch (data_type) {
    case RegisterDataType::kUint16:
    case RegisterDataType::kUint32:
      bits = static_cast<std::uint32_t>(std::llround(std::max(0.0, value)));
      break;
    case RegisterDataType::kInt16:
    case RegisterDataType::kInt32:
      bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(value)));
      break;
    case RegisterDataType::kFloat32:
      bits = std::bit_cast<std::uint32_t>(static_cast<float>(value));
      break;
  }
  if (data_type == RegisterDataType::kUint16 || data_type == RegisterDataType::kInt16) {
    registers[0] = static_cast<std::uint16_t>(bits);
    return;
  }
  const bool big = word_order == WordOrder::kBig;
  registers[big ? 0 : 1] = static_cast<std::uint16_t>(bits >> 16);
  registers[big ? 1 : 0] = static_cast<std::uint16_t>(bits & 0xFFFF);
}

Result<double> illuminanceLx(const IlluminanceConfig& config, double value) {
  const bool lux = config.units == IlluminanceUnits::kLux;
  const double lx = lux ? value : value * config.efficacy_lm_w;
  const std::string reading =
      lux ? fmt::format("{:g} lx", value)
          : fmt::format("{:g} W/m² ({:g} lx at {:g} lm/W)", value, lx, config.efficacy_lm_w);
  if (!std::isfinite(value))
    return hardwareError(fmt::format("{}: reads a value that is not a number", config.where()));
  if (lx <= 0)
    return hardwareError(
        fmt::format("{}: reads {}: no direct light (or a sensor fault)", config.where(), reading));
  if (lx > kMaxSourceIlluminanceLx)
    return hardwareError(fmt::format(
        "{}: reads {}, above {:g} lx, more than any sun gives (wrong scale, units or register?)",
        config.where(), reading, kMaxSourceIlluminanceLx));
  return lx;
}

}  // namespace glarecam::rig
