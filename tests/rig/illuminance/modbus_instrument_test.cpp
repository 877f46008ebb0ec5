// The libmodbus backend's error paths against the real library, without an instrument: a serial
// device that is not there, and an unreachable TCP port. (Its reads are tested against the
// simulated instrument: modbus_simulator_test.cpp.)
#include "rig/illuminance/modbus_instrument.h"

#include <gtest/gtest.h>

#include "core/build_config.h"
#include "rig/illuminance/illuminance_registry.h"

namespace glarecam::rig {
namespace {

IlluminanceConfig rtuConfig() {
  IlluminanceConfig config;
  config.transport = ModbusTransport::kRtu;
  config.device = "/dev/glarecam-no-such-tty";
  config.data_type = RegisterDataType::kFloat32;
  config.units = IlluminanceUnits::kWattPerSquareMetre;
  config.uncertainty_pct = 2;
  return config;
}

#if GLARECAM_WITH_MODBUS

TEST(ModbusInstrumentTest, AMissingSerialDeviceIsAClearError) {
  auto instrument = openModbusInstrument(rtuConfig());
  ASSERT_TRUE(instrument) << instrument.error().message;
  const auto reading = (*instrument)->read();
  ASSERT_FALSE(reading);
  EXPECT_EQ(reading.error().code, ErrorCode::kHardware);
  EXPECT_NE(reading.error().message.find("cannot open /dev/glarecam-no-such-tty"),
            std::string::npos)
      << reading.error().message;
}

TEST(ModbusInstrumentTest, AnInvalidConfigIsRefusedBeforeAnyIo) {
  IlluminanceConfig config = rtuConfig();
  config.slave_id = 0;
  const auto instrument = openModbusInstrument(config);
  ASSERT_FALSE(instrument);
  EXPECT_EQ(instrument.error().code, ErrorCode::kBadInput);
}

TEST(ModbusInstrumentTest, DescribesItselfForTheManifest) {
  auto instrument = openModbusInstrument(rtuConfig());
  ASSERT_TRUE(instrument);
  EXPECT_EQ((*instrument)->info().description,
            "pyrheliometer modbus:/dev/glarecam-no-such-tty@1 (W/m², 93 lm/W)");
  EXPECT_DOUBLE_EQ((*instrument)->info().instrument_u_rel, 0.02);
  EXPECT_DOUBLE_EQ((*instrument)->info().efficacy_u_rel, 8.0 / 93.0);
}

#else

TEST(ModbusInstrumentTest, WithoutLibmodbusOpeningSaysSo) {
  const auto opened = openIlluminance(rtuConfig());
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("without libmodbus"), std::string::npos);
}

#endif

}  // namespace
}  // namespace glarecam::rig
