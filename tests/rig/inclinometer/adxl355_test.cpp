// The ADXL355 driver against the register-level simulator: IDs, configuration, exact conversion
// at each range, temperature, noise, DATA_RDY, each fault as a clear error in bounded time, its
// options, and the adxl355: URI.
#include "rig/inclinometer/adxl355.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "rig/inclinometer/adxl355_simulator.h"
#include "rig/inclinometer/adxl355_test_support.h"

namespace glarecam::rig {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;
using testing::contains;
using testing::gravity;
using testing::kAddress;
using testing::kSimUri;
using testing::openSimulated;
using testing::openSimulatedOrFail;
using testing::rangeOf;
using testing::withFault;

TEST(Adxl355, OpensChecksIdsResetsAndEntersMeasurementMode) {
  auto device = openSimulatedOrFail();
  ASSERT_TRUE(device.inclinometer);
  EXPECT_EQ(device.simulator->resets(), 1);
  EXPECT_TRUE(device.simulator->measuring());
  EXPECT_EQ(device.simulator->rangeG(), 2);
  EXPECT_EQ(device.simulator->outputDataRateHz(), 15.625);
  EXPECT_EQ(device.simulator->registerValue(adxl355::kRegFilter), 0x08);  // ODR_LPF 8, HPF off
  // I2C_HS (bit 7) of the reset value is kept; bits 1:0 select ±2 g.
  EXPECT_EQ(device.simulator->registerValue(adxl355::kRegRange), 0x81);

  const auto& info = device.inclinometer->info();
  EXPECT_EQ(info.uri, kSimUri);
  EXPECT_EQ(info.backend, "adxl355");
  EXPECT_EQ(info.model, "ADXL355");
  EXPECT_EQ(info.full_scale_g, 2.0);
  EXPECT_TRUE(contains(info.detail, "15.625 Hz")) << info.detail;
  EXPECT_TRUE(contains(info.detail, "0x1d on sim-i2c")) << info.detail;
}

TEST(Adxl355, WritesEachRangeAndRate) {
  const std::vector<std::pair<int, double>> settings{
      {2, 4000.0}, {4, 62.5}, {8, 3.906}, {8, 7.8125}};
  for (const auto& [range_g, rate_hz] : settings) {
    Adxl355Options options;
    options.range_g = range_g;
    options.output_data_rate_hz = rate_hz;
    auto device = openSimulatedOrFail({}, options);
    ASSERT_TRUE(device.inclinometer);
    EXPECT_EQ(device.simulator->rangeG(), range_g);
    // 3.906 is the data sheet's rounding of 4000/1024 = 3.90625: the step is matched within 1 mHz.
    EXPECT_NEAR(device.simulator->outputDataRateHz(), rate_hz, 1e-3);
    EXPECT_EQ(device.inclinometer->info().full_scale_g, range_g);
  }
}

TEST(Adxl355, ConvertsExactlyAtEachRange) {
  // Components that are whole codes at every sensitivity (multiples of 1/64000 g, the ±8 g LSB):
  // code / sensitivity is then the correctly rounded double of the component, i.e. equal to it.
  const std::vector<std::array<double, 3>> vectors{
      {0.0, 0.0, 1.0}, {0.5, -0.25, 0.75}, {-1.0, 0.125, -0.5}, {1.75, -1.5, 0.1}};
  for (const int range_g : {2, 4, 8}) {
    for (const auto& vector : vectors) {
      auto device = openSimulatedOrFail(gravity(vector[0], vector[1], vector[2]), rangeOf(range_g));
      ASSERT_TRUE(device.inclinometer);
      const auto sample = device.inclinometer->read();
      ASSERT_TRUE(sample) << sample.error().message;
      EXPECT_EQ(sample->x_g, vector[0]) << "±" << range_g << " g";
      EXPECT_EQ(sample->y_g, vector[1]) << "±" << range_g << " g";
      EXPECT_EQ(sample->z_g, vector[2]) << "±" << range_g << " g";
    }
  }
}

TEST(Adxl355, QuantisesToTheNearestCode) {
  for (const int range_g : {2, 4, 8}) {
    auto device =
        openSimulatedOrFail(gravity(0.123456789, -0.987654321, 0.333333333), rangeOf(range_g));
    ASSERT_TRUE(device.inclinometer);
    const auto sample = device.inclinometer->read();
    ASSERT_TRUE(sample) << sample.error().message;
    // The simulator rounds to the nearest code: within half an LSB.
    const double half_lsb_g = 0.5 / adxl355::sensitivityLsbPerG(range_g);
    EXPECT_NEAR(sample->x_g, 0.123456789, half_lsb_g);
    EXPECT_NEAR(sample->y_g, -0.987654321, half_lsb_g);
    EXPECT_NEAR(sample->z_g, 0.333333333, half_lsb_g);
  }
}

TEST(Adxl355, ReadsTheTemperature) {
  auto simulator_options = gravity(0, 0, 1);
  simulator_options.temperature_c = 25.0;
  auto device = openSimulatedOrFail(simulator_options);
  ASSERT_TRUE(device.inclinometer);
  auto sample = device.inclinometer->read();
  ASSERT_TRUE(sample) << sample.error().message;
  ASSERT_TRUE(sample->temperature_c);
  EXPECT_EQ(*sample->temperature_c, 25.0);  // the intercept, 1885 LSB, is a whole code

  for (const double temperature_c : {-20.0, 0.0, 40.0, 85.0}) {
    device.simulator->setTemperature(temperature_c);
    sample = device.inclinometer->read();
    ASSERT_TRUE(sample) << sample.error().message;
    ASSERT_TRUE(sample->temperature_c);
    // 12-bit code at 9.05 LSB/°C: within half a code, 0.5 / 9.05 °C.
    EXPECT_NEAR(*sample->temperature_c, temperature_c, 0.5 / 9.05);
  }
}

TEST(Adxl355, FollowsATilt) {
  auto device = openSimulatedOrFail();
  ASSERT_TRUE(device.inclinometer);
  auto sample = device.inclinometer->read();
  ASSERT_TRUE(sample);
  EXPECT_EQ(sample->z_g, 1.0);
  device.simulator->setGravity(0.5, 0.0, 0.75);
  sample = device.inclinometer->read();
  ASSERT_TRUE(sample);
  EXPECT_EQ(sample->x_g, 0.5);
  EXPECT_EQ(sample->z_g, 0.75);
}

TEST(Adxl355, NoiseHasTheConfiguredSpreadAndIsDeterministic) {
  auto simulator_options = gravity(0.0, 0.0, 1.0);
  simulator_options.noise_g = 0.01;
  simulator_options.seed = 42;
  auto device = openSimulatedOrFail(simulator_options);
  auto twin = openSimulatedOrFail(simulator_options);
  ASSERT_TRUE(device.inclinometer && twin.inclinometer);

  constexpr int kSamples = 4000;
  double sum = 0.0, sum_squares = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const auto sample = device.inclinometer->read();
    const auto same = twin.inclinometer->read();
    ASSERT_TRUE(sample && same);
    ASSERT_EQ(sample->x_g, same->x_g);  // same seed, same sequence
    sum += sample->x_g;
    sum_squares += sample->x_g * sample->x_g;
  }
  const double mean = sum / kSamples;
  const double sigma = std::sqrt(sum_squares / kSamples - mean * mean);
  // Mean of N draws of σ 0.01 g: within 5 standard errors (σ/√N), a false alarm ~1e-6.
  EXPECT_NEAR(mean, 0.0, 5 * 0.01 / std::sqrt(kSamples));
  // Sample σ has relative standard error 1/√(2N) ≈ 1.1 %; 6 % is over 5 of them (the 3.9 µg
  // quantisation adds nothing visible to a 10 mg σ).
  EXPECT_NEAR(sigma, 0.01, 0.06 * 0.01);

  // Another seed, another sequence.
  auto again = openSimulatedOrFail(simulator_options);
  simulator_options.seed = 43;
  auto other = openSimulatedOrFail(simulator_options);
  ASSERT_TRUE(again.inclinometer && other.inclinometer);
  const auto first_again = again.inclinometer->read();
  const auto first_other = other.inclinometer->read();
  ASSERT_TRUE(first_again && first_other);
  EXPECT_NE(first_again->x_g, first_other->x_g);
}

TEST(Adxl355, WaitsForDataReadyAndReadsEachSampleOnce) {
  auto simulator_options = gravity(0, 0, 1);
  simulator_options.status_reads_per_sample = 3;  // DATA_RDY appears on the 4th STATUS read
  Adxl355Options options;
  options.output_data_rate_hz = 4000.0;  // a quarter period is 62.5 µs: polls sleep 100 µs
  auto device = openSimulatedOrFail(simulator_options, options);
  ASSERT_TRUE(device.inclinometer);
  for (int i = 1; i <= 5; ++i) {
    const auto sample = device.inclinometer->read();
    ASSERT_TRUE(sample) << sample.error().message;
    EXPECT_EQ(device.simulator->samplesProduced(), i);
    EXPECT_EQ(device.simulator->dataReads(), i);
    // One burst per sample: X, Y, Z and temperature in the same transaction.
    EXPECT_FALSE(device.simulator->registerValue(adxl355::kRegStatus) & adxl355::kStatusDataReady);
  }
}

TEST(Adxl355, AbsentDeviceIsAHardwareErrorNamingAddressAndBus) {
  const auto opened = openSimulated(withFault(Adxl355SimulatorFault::kAbsent));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(opened.error().message, "no device answers at 0x1d on sim-i2c"))
      << opened.error().message;
}

TEST(Adxl355, WrongAddressIsANack) {
  Adxl355SimulatorOptions simulator_options;
  simulator_options.address = kAdxl355AddressAselHigh;
  const auto opened = openSimulated(simulator_options, {}, kAdxl355AddressAselLow);
  ASSERT_FALSE(opened);
  EXPECT_TRUE(contains(opened.error().message, "no device answers at 0x1d"))
      << opened.error().message;
  EXPECT_TRUE(openSimulated(simulator_options, {}, kAdxl355AddressAselHigh));
}

TEST(Adxl355, WrongIdsNameWhatWasRead) {
  const auto opened = openSimulated(withFault(Adxl355SimulatorFault::kWrongId));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(opened.error().message,
                       "device at 0x1d on sim-i2c is not an ADXL355 (DEVID_AD 0xe5"))
      << opened.error().message;
  EXPECT_TRUE(contains(opened.error().message, "PARTID 0x00")) << opened.error().message;
}

TEST(Adxl355, AllZeroAxesAreAnError) {
  auto device = openSimulatedOrFail(withFault(Adxl355SimulatorFault::kAllZero));
  ASSERT_TRUE(device.inclinometer);
  const auto sample = device.inclinometer->read();
  ASSERT_FALSE(sample);
  EXPECT_EQ(sample.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(sample.error().message, "all three axes read exactly 0"))
      << sample.error().message;
}

TEST(Adxl355, SaturationIsAnError) {
  auto device = openSimulatedOrFail(withFault(Adxl355SimulatorFault::kSaturated));
  ASSERT_TRUE(device.inclinometer);
  auto sample = device.inclinometer->read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "X axis saturated")) << sample.error().message;

  // Beyond the range, the simulated part clamps at the full-scale codes, both signs.
  auto beyond = openSimulatedOrFail(gravity(0.0, 3.0, 1.0));
  sample = beyond.inclinometer->read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "Y axis saturated (code 524287"))
      << sample.error().message;
  beyond.simulator->setGravity(0.0, 0.0, -2.5);
  sample = beyond.inclinometer->read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "Z axis saturated (code -524288"))
      << sample.error().message;
  // The same tilt fits in ±4 g.
  auto wider = openSimulatedOrFail(gravity(0.0, 3.0, 1.0), rangeOf(4));
  ASSERT_TRUE(wider.inclinometer->read());
}

TEST(Adxl355, NeverReadyTimesOutInBoundedTime) {
  Adxl355Options options;
  options.output_data_rate_hz = 1000.0;
  options.data_ready_timeout = milliseconds(30);
  auto device = openSimulatedOrFail(withFault(Adxl355SimulatorFault::kNeverReady), options);
  ASSERT_TRUE(device.inclinometer);
  const auto start = Clock::now();
  const auto sample = device.inclinometer->read();
  const auto elapsed = Clock::now() - start;
  ASSERT_FALSE(sample);
  EXPECT_EQ(sample.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(sample.error().message, "no new sample within 30 ms"))
      << sample.error().message;
  EXPECT_GE(elapsed, milliseconds(30));
  // Bounded: the last sleep is cut at the deadline; 500 ms of slack for a loaded machine.
  EXPECT_LT(elapsed, milliseconds(530));
  // Polls a quarter period apart (250 µs) for 30 ms: about 120, far from a busy loop.
  EXPECT_LT(device.simulator->transactions(), 400);
}

TEST(Adxl355, OptionsAreValidated) {
  EXPECT_TRUE(Adxl355Options{}.validate());
  Adxl355Options options;
  options.range_g = 3;
  EXPECT_TRUE(contains(options.validate().error().message, "±2, ±4 or ±8 g"));
  options = {};
  options.output_data_rate_hz = 100.0;
  EXPECT_TRUE(contains(options.validate().error().message, "15.625"));
  options = {};
  options.output_data_rate_hz = std::nan("");
  EXPECT_FALSE(options.validate());
  options = {};
  options.data_ready_timeout = milliseconds(0);
  EXPECT_FALSE(options.validate());
  options = {};
  options.output_data_rate_hz = 3.906;
  options.data_ready_timeout = milliseconds(100);  // shorter than the 256 ms period
  EXPECT_TRUE(contains(options.validate().error().message, "256 ms"))
      << options.validate().error().message;
  options.data_ready_timeout = milliseconds(120'000);
  EXPECT_FALSE(options.validate());

  // openAdxl355 refuses them before touching the bus.
  const auto opened =
      openAdxl355(std::make_unique<Adxl355Simulator>(), kAddress, rangeOf(16), "adxl355:x");
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kBadInput);
}

TEST(Adxl355Uri, ParsesPathAndAddress) {
  auto parsed = parseAdxl355Id("/dev/i2c-1@0x1d");
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ(parsed->bus_path, "/dev/i2c-1");
  EXPECT_EQ(parsed->address, 0x1D);

  parsed = parseAdxl355Id("/dev/i2c-1");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->bus_path, "/dev/i2c-1");
  EXPECT_EQ(parsed->address, kAdxl355AddressAselLow);  // the default

  parsed = parseAdxl355Id("/dev/i2c-20@0X53");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->bus_path, "/dev/i2c-20");
  EXPECT_EQ(parsed->address, 0x53);

  parsed = parseAdxl355Id("/dev/i2c-1@83");  // decimal
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->address, 0x53);

  parsed = parseAdxl355Id("/dev/bus@2/i2c@0x1d");  // the last '@' separates the address
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->bus_path, "/dev/bus@2/i2c");
}

TEST(Adxl355Uri, RejectsBadFormsNamingTheUri) {
  for (const std::string_view id :
       {"", "@0x1d", "dev/i2c-1", "i2c-1@0x1d", "/dev/i2c-1@", "/dev/i2c-1@0x", "/dev/i2c-1@0x1g",
        "/dev/i2c-1@0x80", "/dev/i2c-1@0x00", "/dev/i2c-1@0x02", "/dev/i2c-1@0x78", "/dev/i2c-1@-1",
        "/dev/i2c-1@+29", "/dev/i2c-1@0x1d ", "/dev/i2c-1@1d"}) {
    const auto parsed = parseAdxl355Id(id);
    ASSERT_FALSE(parsed) << "'" << id << "'";
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput) << id;
    EXPECT_TRUE(contains(parsed.error().message, "adxl355:" + std::string(id) + ":"))
        << parsed.error().message;
  }
}

TEST(Adxl355Uri, ParsesI2cAddresses) {
  EXPECT_EQ(parseI2cAddress("0x03").value(), 0x03);
  EXPECT_EQ(parseI2cAddress("0x77").value(), 0x77);
  EXPECT_EQ(parseI2cAddress("29").value(), 0x1D);
  EXPECT_FALSE(parseI2cAddress("0x1d0"));
  EXPECT_FALSE(parseI2cAddress(""));
}

}  // namespace
}  // namespace glarecam::rig
