// The libmodbus backend against the simulated instrument on loopback: every entry of the
// documented register map, and each fault a clear error, never a number.
#include "rig/illuminance/modbus_simulator.h"

#include <gtest/gtest.h>

#include <chrono>

#include "core/build_config.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/illuminance/illuminance_test_support.h"
#include "rig/illuminance/modbus_instrument.h"

namespace glarecam::rig {
namespace {

#if GLARECAM_WITH_MODBUS

constexpr double kServedLx = 93'000.0;  // 1000 W/m² at 93 lm/W

IlluminanceConfig loopback(int port, int address, RegisterDataType type, double scale,
                           IlluminanceUnits units, WordOrder order = WordOrder::kBig) {
  IlluminanceConfig config;
  config.transport = ModbusTransport::kTcp;
  config.host = "127.0.0.1";
  config.port = port;
  config.address = address;
  config.data_type = type;
  config.word_order = order;
  config.scale = scale;
  config.units = units;
  config.uncertainty_pct = 2;
  config.timeout = std::chrono::milliseconds(150);  // the timeout test waits this long
  return config;
}

struct Served {
  std::unique_ptr<ModbusInstrumentSimulator> simulator;
  Served() {
    auto started = ModbusInstrumentSimulator::start({.illuminance_lx = kServedLx});
    EXPECT_TRUE(started) << started.error().message;
    simulator = std::move(*started);
  }
  Result<IlluminanceReading> readOnce(const IlluminanceConfig& config) const {
    auto instrument = openModbusInstrument(config);
    if (!instrument) return std::unexpected(instrument.error());
    return (*instrument)->read();
  }
  IlluminanceConfig irradiance() const {
    return loopback(simulator->port(), 0, RegisterDataType::kFloat32, 1,
                    IlluminanceUnits::kWattPerSquareMetre);
  }
};

TEST(ModbusSimulatorTest, ServesEveryEntryOfTheRegisterMap) {
  Served served;
  const int port = served.simulator->port();
  const auto w_m2 = IlluminanceUnits::kWattPerSquareMetre;
  const auto lx = IlluminanceUnits::kLux;
  struct Entry {
    IlluminanceConfig config;
    double tolerance_lx;  // the register's resolution, in lx
  };
  const Entry entries[] = {
      {loopback(port, 0, RegisterDataType::kFloat32, 1, w_m2), 0.01},
      {loopback(port, 2, RegisterDataType::kFloat32, 1, w_m2, WordOrder::kLittle), 0.01},
      {loopback(port, 4, RegisterDataType::kUint16, 0.1, w_m2), 0.1 * 93},
      {loopback(port, 5, RegisterDataType::kInt16, 0.1, w_m2), 0.1 * 93},
      {loopback(port, 6, RegisterDataType::kUint32, 0.001, w_m2), 0.001 * 93},
      {loopback(port, 8, RegisterDataType::kFloat32, 1, lx), 0.01},
      {loopback(port, 10, RegisterDataType::kUint16, 10, lx), 10},
  };
  for (const Entry& entry : entries) {
    for (const RegisterType type : {RegisterType::kInput, RegisterType::kHolding}) {
      IlluminanceConfig config = entry.config;
      config.register_type = type;
      const auto reading = served.readOnce(config);
      ASSERT_TRUE(reading) << config.address << ": " << reading.error().message;
      EXPECT_NEAR(reading->illuminance_lx, kServedLx, entry.tolerance_lx) << config.address;
    }
  }
}

TEST(ModbusSimulatorTest, FollowsTheValueItIsGiven) {
  Served served;
  auto instrument = openModbusInstrument(served.irradiance());
  ASSERT_TRUE(instrument);
  served.simulator->setIlluminanceLx(46'500);
  const auto reading = (*instrument)->read();
  ASSERT_TRUE(reading) << reading.error().message;
  EXPECT_NEAR(reading->raw_value, 500.0, 1e-3);  // W/m²
  EXPECT_NEAR(reading->illuminance_lx, 46'500, 0.1);
}

TEST(ModbusSimulatorTest, AnAddressOutsideTheMapIsAnExceptionReply) {
  Served served;
  IlluminanceConfig config = served.irradiance();
  config.address = 40;
  const auto reading = served.readOnce(config);
  ASSERT_FALSE(reading);
  EXPECT_EQ(reading.error().code, ErrorCode::kHardware);
  EXPECT_NE(reading.error().message.find("exception reply"), std::string::npos)
      << reading.error().message;
}

TEST(ModbusSimulatorTest, ADeadInstrumentRefusesTheConnection) {
  auto simulator = ModbusInstrumentSimulator::start({.fault = SimulatedInstrumentFault::kDead});
  ASSERT_TRUE(simulator);
  auto instrument =
      openModbusInstrument(loopback((*simulator)->port(), 0, RegisterDataType::kFloat32, 1,
                                    IlluminanceUnits::kWattPerSquareMetre));
  ASSERT_TRUE(instrument) << instrument.error().message;  // connected at the first read
  const auto reading = (*instrument)->read();
  ASSERT_FALSE(reading);
  EXPECT_EQ(reading.error().code, ErrorCode::kHardware);
  EXPECT_NE(reading.error().message.find("connection refused"), std::string::npos)
      << reading.error().message;
  EXPECT_NE(reading.error().message.find("127.0.0.1"), std::string::npos);
  // Back: the backend connects again at the next read.
  (*simulator)->setFault(SimulatedInstrumentFault::kNone);
  Result<IlluminanceReading> again = std::unexpected(Error{});
  for (int attempt = 0; attempt < 50 && !again; ++attempt) {
    again = (*instrument)->read();
    if (!again) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_NEAR(again->illuminance_lx, 90'000, 0.1);
}

TEST(ModbusSimulatorTest, ASilentInstrumentTimesOut) {
  Served served;
  served.simulator->setFault(SimulatedInstrumentFault::kTimeout);
  const auto started = std::chrono::steady_clock::now();
  const auto reading = served.readOnce(served.irradiance());
  ASSERT_FALSE(reading);
  EXPECT_NE(reading.error().message.find("no reply within 150 ms"), std::string::npos)
      << reading.error().message;
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(2));
}

TEST(ModbusSimulatorTest, AnotherSlaveIdGetsNoReply) {
  Served served;
  IlluminanceConfig config = served.irradiance();
  config.slave_id = 7;
  const auto reading = served.readOnce(config);
  ASSERT_FALSE(reading);
  EXPECT_NE(reading.error().message.find("slave_id 7"), std::string::npos)
      << reading.error().message;
}

TEST(ModbusSimulatorTest, AnExceptionReplyIsNamed) {
  Served served;
  served.simulator->setFault(SimulatedInstrumentFault::kException);
  const auto reading = served.readOnce(served.irradiance());
  ASSERT_FALSE(reading);
  EXPECT_NE(reading.error().message.find("exception reply"), std::string::npos)
      << reading.error().message;
  EXPECT_GE(served.simulator->requestsAnswered(), 1);
}

TEST(ModbusSimulatorTest, OutOfRangeAndNegativeValuesAreRefused) {
  Served served;
  for (const SimulatedInstrumentFault fault :
       {SimulatedInstrumentFault::kOutOfRange, SimulatedInstrumentFault::kNegative}) {
    served.simulator->setFault(fault);
    for (const int address : {0, 8}) {  // W/m² and lx
      IlluminanceConfig config = served.irradiance();
      config.address = address;
      if (address == 8) config.units = IlluminanceUnits::kLux;
      const auto reading = served.readOnce(config);
      ASSERT_FALSE(reading) << address << " " << reading->illuminance_lx;
      EXPECT_EQ(reading.error().code, ErrorCode::kHardware);
      EXPECT_NE(reading.error().message.find(fault == SimulatedInstrumentFault::kOutOfRange
                                                 ? "more than any sun gives"
                                                 : "no direct light"),
                std::string::npos)
          << reading.error().message;
    }
  }
}

TEST(ModbusSimulatorTest, TheSimTransportServesAndReadsThroughTheSameBackend) {
  IlluminanceConfig config = testing::simulatedHeadConfig();
  auto opened = openIlluminance(config, 70'000);
  ASSERT_TRUE(opened) << opened.error().message;
  ASSERT_TRUE(opened->simulator);
  const auto reading = opened->instrument->read();
  ASSERT_TRUE(reading) << reading.error().message;
  EXPECT_NEAR(reading->illuminance_lx, 70'000, 0.1);
  EXPECT_NE(opened->instrument->info().description.find("modbus:sim:127.0.0.1:"),
            std::string::npos);
}

#else

TEST(ModbusSimulatorTest, NeedsLibmodbus) {
  GTEST_SKIP() << "built without libmodbus (GLARECAM_WITH_MODBUS=OFF)";
}

#endif

}  // namespace
}  // namespace glarecam::rig
