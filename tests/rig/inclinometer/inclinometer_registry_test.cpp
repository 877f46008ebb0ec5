// Inclinometers by URI: bad schemes and forms, the sim: inclinometer and its faults, and the real
// buses' errors on a machine without them.
#include "rig/inclinometer/inclinometer_registry.h"

#include <gtest/gtest.h>

#include <string>

#include "rig/inclinometer/tilt.h"

namespace glarecam::rig {
namespace {

TEST(InclinometerRegistry, UnknownSchemesAndMalformedUrisAreBadInput) {
  for (const char* uri : {"", "sim", "adxl", "foo:bar", "/dev/i2c-1"}) {
    const auto opened = openInclinometer(uri);
    ASSERT_FALSE(opened) << uri;
    EXPECT_EQ(opened.error().code, ErrorCode::kBadInput) << uri;
  }
  for (const char* uri :
       {"sim:", "sim:abc", "sim:30,noise_g", "sim:30,noise_g=-1", "sim:30,colour=red",
        "sim:30,fault=smoke", "sim:200", "sim:30,seed=1.5"}) {
    const auto opened = openInclinometer(uri);
    ASSERT_FALSE(opened) << uri;
    EXPECT_EQ(opened.error().code, ErrorCode::kBadInput) << uri;
    EXPECT_NE(opened.error().message.find("inclinometer URI sim:"), std::string::npos)
        << opened.error().message;
  }
}

TEST(InclinometerRegistry, SimReadsItsTilt) {
  auto sensor = openInclinometer("sim:25,roll_deg=-3,noise_g=0");
  ASSERT_TRUE(sensor) << sensor.error().message;
  EXPECT_EQ((*sensor)->info().backend, "sim");
  const auto reading = measureTilt(**sensor, {});
  ASSERT_TRUE(reading) << reading.error().message;
  // Noise-free: the only error is the ADXL355's 20-bit quantisation, 3.9 µg ≈ 0.0002° at ±2 g.
  EXPECT_NEAR(reading->tilt.x_deg, 25, 5e-4);
  EXPECT_NEAR(reading->tilt.y_deg, -3, 5e-4);
}

TEST(InclinometerRegistry, SimFaultsAreErrorsNotHangs) {
  for (const char* fault : {"absent", "wrong-id"}) {
    const auto opened = openInclinometer(std::string("sim:0,fault=") + fault);
    ASSERT_FALSE(opened) << fault;
    EXPECT_EQ(opened.error().code, ErrorCode::kHardware) << fault;
  }
  for (const char* fault : {"zeros", "saturated", "never-ready"}) {
    auto sensor = openInclinometer(std::string("sim:0,fault=") + fault);
    ASSERT_TRUE(sensor) << fault << ": " << sensor.error().message;
    const auto sample = (*sensor)->read();
    ASSERT_FALSE(sample) << fault;
    EXPECT_EQ(sample.error().code, ErrorCode::kHardware) << fault;
  }
}

TEST(InclinometerRegistry, RealBusesAbsentHereFailClearly) {
  const auto i2c = openInclinometer("adxl355:/dev/i2c-97@0x1d");
  ASSERT_FALSE(i2c);
  EXPECT_EQ(i2c.error().code, ErrorCode::kHardware);
  EXPECT_NE(i2c.error().message.find("/dev/i2c-97"), std::string::npos) << i2c.error().message;
  const auto iio = openInclinometer("iio:iio:device97");
  ASSERT_FALSE(iio);
  EXPECT_NE(iio.error().message.find("iio:device97"), std::string::npos) << iio.error().message;
}

}  // namespace
}  // namespace glarecam::rig
