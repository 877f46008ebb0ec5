// The ADXL355 register simulator itself: burst reads, reset, no samples in standby, and its
// real-time mode pacing samples at the output data rate.
#include "rig/inclinometer/adxl355_simulator.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>

#include "rig/inclinometer/adxl355.h"
#include "rig/inclinometer/adxl355_test_support.h"

namespace glarecam::rig {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;
using testing::gravity;
using testing::kAddress;
using testing::openSimulatedOrFail;

TEST(Adxl355, RealTimeSimulatorPacesSamplesAtTheOutputDataRate) {
  auto simulator_options = gravity(0, 0, 1);
  simulator_options.real_time = true;
  Adxl355Options options;
  options.output_data_rate_hz = 1000.0;
  auto device = openSimulatedOrFail(simulator_options, options);
  ASSERT_TRUE(device.inclinometer);
  constexpr int kReads = 20;
  const auto start = Clock::now();
  for (int i = 0; i < kReads; ++i) ASSERT_TRUE(device.inclinometer->read());
  // Samples arrive on a 1 ms grid, at most one per grid point: 20 samples span more than 18 ms
  // (the first and last may sit at the ends of their periods). A lower bound only: a loaded
  // machine may be slower, never faster.
  EXPECT_GE(Clock::now() - start, milliseconds(kReads - 2));
  EXPECT_EQ(device.simulator->samplesProduced(), kReads);
}

TEST(Adxl355, NoSamplesInStandby) {
  Adxl355Simulator simulator;
  const std::array<std::uint8_t, 1> status_pointer{adxl355::kRegStatus};
  std::array<std::uint8_t, 1> status{};
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(simulator.transfer(kAddress, status_pointer, status));
    EXPECT_EQ(status[0] & adxl355::kStatusDataReady, 0);
  }
  EXPECT_EQ(simulator.samplesProduced(), 0);
  EXPECT_FALSE(simulator.measuring());
}

TEST(Adxl355Simulator, BurstReadsAutoIncrementAndResetRestoresDefaults) {
  Adxl355Simulator simulator;
  const std::array<std::uint8_t, 1> id_pointer{adxl355::kRegDevIdAd};
  std::array<std::uint8_t, 4> ids{};
  ASSERT_TRUE(simulator.transfer(kAddress, id_pointer, ids));
  EXPECT_EQ(ids, (std::array<std::uint8_t, 4>{0xAD, 0x1D, 0xED, 0x01}));

  const std::array<std::uint8_t, 2> set_range{adxl355::kRegRange, 0x83};
  ASSERT_TRUE(simulator.transfer(kAddress, set_range, {}));
  EXPECT_EQ(simulator.rangeG(), 8);
  const std::array<std::uint8_t, 2> reset{adxl355::kRegReset, adxl355::kResetCode};
  ASSERT_TRUE(simulator.transfer(kAddress, reset, {}));
  EXPECT_EQ(simulator.rangeG(), 2);
  EXPECT_EQ(simulator.resets(), 1);
  EXPECT_EQ(simulator.transactions(), 3);
}

}  // namespace
}  // namespace glarecam::rig
