#include "rig/illuminance/illuminance_config.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "rig/rig_config_test_support.h"

namespace glarecam::rig {
namespace {

using testing::readRigConfig;
using testing::TempDir;
using testing::writeText;

constexpr const char* kRtuTable = R"([illuminance]
transport = "rtu"
device = "/dev/ttyUSB0"
baud = 19200
parity = "even"
slave_id = 3
register_type = "holding"
address = 100
data_type = "int32"
word_order = "little"
scale = 0.1
units = "W/m2"
uncertainty_pct = 1.5
efficacy_lm_w = 95
efficacy_u_lm_w = 6
timeout_ms = 250
sample_interval_ms = 50
name = "CHP1 pyrheliometer"
)";

Result<RigConfig> readTable(const TempDir& dir, const std::string& text) {
  return readRigConfig(writeText(dir, "rig.toml", text));
}

TEST(IlluminanceConfigTest, ReadsEveryKey) {
  TempDir dir;
  const auto rig = readTable(dir, kRtuTable);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->illuminance);
  const IlluminanceConfig& config = *rig->illuminance;
  EXPECT_EQ(config.transport, ModbusTransport::kRtu);
  EXPECT_EQ(config.device, "/dev/ttyUSB0");
  EXPECT_EQ(config.baud, 19200);
  EXPECT_EQ(config.parity, 'E');
  EXPECT_EQ(config.slave_id, 3);
  EXPECT_EQ(config.register_type, RegisterType::kHolding);
  EXPECT_EQ(config.address, 100);
  EXPECT_EQ(config.data_type, RegisterDataType::kInt32);
  EXPECT_EQ(config.word_order, WordOrder::kLittle);
  EXPECT_DOUBLE_EQ(config.scale, 0.1);
  EXPECT_EQ(config.units, IlluminanceUnits::kWattPerSquareMetre);
  EXPECT_DOUBLE_EQ(config.uncertainty_pct, 1.5);
  EXPECT_DOUBLE_EQ(config.efficacy_lm_w, 95);
  EXPECT_DOUBLE_EQ(config.efficacy_u_lm_w, 6);
  EXPECT_EQ(config.timeout.count(), 250);
  EXPECT_EQ(config.sample_interval.count(), 50);
  EXPECT_EQ(config.description(), "CHP1 pyrheliometer modbus:/dev/ttyUSB0@3 (W/m², 95 lm/W)");
}

TEST(IlluminanceConfigTest, DefaultsToTheStatedEfficacy) {
  TempDir dir;
  const auto rig = readTable(dir, R"([illuminance]
transport = "tcp"
host = "10.0.0.7"
data_type = "float32"
units = "W/m2"
uncertainty_pct = 2
)");
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_DOUBLE_EQ(rig->illuminance->efficacy_lm_w, kDefaultDirectEfficacyLmW);
  EXPECT_DOUBLE_EQ(rig->illuminance->efficacy_u_lm_w, kDefaultDirectEfficacyULmW);
  EXPECT_EQ(rig->illuminance->port, 502);
  EXPECT_EQ(rig->illuminance->where(), "modbus:tcp:10.0.0.7:502@1");
}

// Each bad value is one line naming the file, the line and the key.
TEST(IlluminanceConfigTest, RefusesBadValuesNamingFileAndKey) {
  const std::string base = "[illuminance]\ntransport = \"tcp\"\nhost = \"h\"\n";
  const std::array<std::pair<std::string, std::string>, 12> cases{{
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\nslave_id = 0\n",
       "illuminance.slave_id"},
      {"data_type = \"float64\"\nunits = \"W/m2\"\nuncertainty_pct = 2\n", "illuminance.data_type"},
      {"data_type = \"float32\"\nunits = \"klx\"\nuncertainty_pct = 2\n", "illuminance.units"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\n", "uncertainty_pct"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = -1\n",
       "illuminance.uncertainty_pct"},
      {"data_type = \"float32\"\nunits = \"lx\"\nuncertainty_pct = 2\nefficacy_lm_w = 93\n",
       "illuminance.efficacy_lm_w"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\nefficacy_lm_w = 930\n",
       "illuminance.efficacy_lm_w"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\naddress = 70000\n",
       "illuminance.address"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\ntimeout_ms = 0\n",
       "illuminance.timeout_ms"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\nscale = nan\n",
       "illuminance.scale"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\nsim_fault = \"dead\"\n",
       "sim_fault"},
      {"data_type = \"float32\"\nunits = \"W/m2\"\nuncertainty_pct = 2\nbaudrate = 9600\n",
       "baudrate"},
  }};
  for (const auto& [keys, named] : cases) {
    TempDir dir;
    const auto rig = readTable(dir, base + keys);
    ASSERT_FALSE(rig) << keys;
    EXPECT_EQ(rig.error().code, ErrorCode::kBadInput);
    EXPECT_NE(rig.error().message.find((dir / "rig.toml").string() + ":"), std::string::npos)
        << rig.error().message;
    EXPECT_NE(rig.error().message.find(named), std::string::npos) << rig.error().message;
    EXPECT_EQ(rig.error().message.find('\n'), std::string::npos) << rig.error().message;
  }
}

TEST(IlluminanceConfigTest, TransportNeedsItsAddress) {
  TempDir dir;
  const auto rig = readTable(dir, R"([illuminance]
transport = "rtu"
data_type = "uint16"
units = "lx"
uncertainty_pct = 3
)");
  ASSERT_FALSE(rig);
  EXPECT_NE(rig.error().message.find("device"), std::string::npos) << rig.error().message;
}

TEST(IlluminanceConfigTest, DecodesEveryDataTypeAndWordOrder) {
  IlluminanceConfig config;
  for (const RegisterDataType type :
       {RegisterDataType::kUint16, RegisterDataType::kInt16, RegisterDataType::kUint32,
        RegisterDataType::kInt32, RegisterDataType::kFloat32}) {
    for (const WordOrder order : {WordOrder::kBig, WordOrder::kLittle}) {
      config.data_type = type;
      config.word_order = order;
      config.scale = 0.5;
      std::array<std::uint16_t, 2> registers{};
      const bool is_signed = type == RegisterDataType::kInt16 || type == RegisterDataType::kInt32;
      const double value = is_signed ? -1234 : 31234;
      encodeRegisters(type, order, value,
                      std::span(registers).first(static_cast<std::size_t>(config.registerCount())));
      EXPECT_DOUBLE_EQ(
          decodeRegisters(
              config, std::span(registers).first(static_cast<std::size_t>(config.registerCount()))),
          value * 0.5);
    }
  }
}

TEST(IlluminanceConfigTest, WordOrderIsWhichRegisterHoldsTheHighWord) {
  IlluminanceConfig config;
  config.data_type = RegisterDataType::kUint32;
  const std::array<std::uint16_t, 2> registers{0x0001, 0x0002};
  config.word_order = WordOrder::kBig;
  EXPECT_DOUBLE_EQ(decodeRegisters(config, registers), 65538.0);
  config.word_order = WordOrder::kLittle;
  EXPECT_DOUBLE_EQ(decodeRegisters(config, registers), 131073.0);
  // IEEE 754 1000.0f is 0x447A0000: high word first.
  config.data_type = RegisterDataType::kFloat32;
  config.word_order = WordOrder::kBig;
  EXPECT_DOUBLE_EQ(decodeRegisters(config, std::array<std::uint16_t, 2>{0x447A, 0x0000}), 1000.0);
}

TEST(IlluminanceConfigTest, ConvertsIrradianceWithTheEfficacy) {
  IlluminanceConfig config;
  config.units = IlluminanceUnits::kWattPerSquareMetre;
  config.efficacy_lm_w = 93;
  const auto lx = illuminanceLx(config, 1000.0);
  ASSERT_TRUE(lx) << lx.error().message;
  EXPECT_DOUBLE_EQ(*lx, 93'000.0);
  config.units = IlluminanceUnits::kLux;
  EXPECT_DOUBLE_EQ(*illuminanceLx(config, 93'000.0), 93'000.0);
}

// A value no sun gives, a negative or zero one, or not a number: an error, never a number.
TEST(IlluminanceConfigTest, RefusesAbsurdReadings) {
  IlluminanceConfig config;
  config.transport = ModbusTransport::kTcp;
  config.host = "h";
  config.units = IlluminanceUnits::kWattPerSquareMetre;
  for (const double w_m2 : {2000.0, -5.0, 0.0, std::nan("")}) {
    const auto lx = illuminanceLx(config, w_m2);
    ASSERT_FALSE(lx) << w_m2;
    EXPECT_EQ(lx.error().code, ErrorCode::kHardware);
    EXPECT_NE(lx.error().message.find("modbus:tcp:h:502@1"), std::string::npos);
  }
  config.units = IlluminanceUnits::kLux;
  EXPECT_FALSE(illuminanceLx(config, 150'001.0));
  EXPECT_TRUE(illuminanceLx(config, 150'000.0));
}

}  // namespace
}  // namespace glarecam::rig
