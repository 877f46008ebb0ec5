#include "rig/illuminance/illuminance_sampler.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <deque>
#include <thread>

#include "core/build_config.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/illuminance/illuminance_test_support.h"
#include "rig/illuminance/modbus_simulator.h"

namespace glarecam::rig {
namespace {

using Clock = std::chrono::steady_clock;

// Readings as scripted; past the script, the last one again. `age` backdates each reading's
// request (an instrument that answers from a cache, say).
class ScriptedInstrument final : public IlluminanceInstrument {
 public:
  explicit ScriptedInstrument(std::vector<Result<double>> script) : script_(std::move(script)) {
    info_ = {.description = "scripted", .instrument_u_rel = 0.02, .efficacy_u_rel = 0.05};
  }
  const IlluminanceInstrumentInfo& info() const override { return info_; }
  Result<IlluminanceReading> read() override {
    const std::size_t at = std::min<std::size_t>(reads_++, script_.size() - 1);
    if (!script_[at]) return std::unexpected(script_[at].error());
    return IlluminanceReading{.illuminance_lx = *script_[at],
                              .raw_value = *script_[at],
                              .requested_at = Clock::now() - age};
  }
  std::chrono::milliseconds age{0};
  std::atomic<std::size_t> reads_{0};

 private:
  std::vector<Result<double>> script_;
  IlluminanceInstrumentInfo info_;
};

TEST(IlluminanceSamplerTest, SummarisesMeanSpreadAndCombinedUncertainty) {
  const Clock::time_point start = Clock::now();
  const IlluminanceInstrumentInfo info{
      .description = "x", .instrument_u_rel = 0.02, .efficacy_u_rel = 0.05};
  std::vector<IlluminanceReading> readings;
  for (const double lx : {90'000.0, 92'000.0, 94'000.0, 96'000.0})
    readings.push_back({.illuminance_lx = lx, .raw_value = lx, .requested_at = start});
  const auto source = summariseReadings(readings, info, start);
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_DOUBLE_EQ(source->illuminance_lx, 93'000);
  EXPECT_EQ(source->samples, 4);
  const double spread = std::sqrt((9.0 + 1 + 1 + 9) * 1e6 / 3);  // sample standard deviation
  EXPECT_NEAR(*source->spread_lx, spread, 1e-9);
  const double u =
      std::sqrt(std::pow(spread / 2, 2) + std::pow(0.02 * 93'000, 2) + std::pow(0.05 * 93'000, 2));
  EXPECT_NEAR(source->illuminance_u_lx, u, 1e-9);
  EXPECT_EQ(source->origin, IlluminanceOrigin::kSensor);
  EXPECT_EQ(source->instrument, "x");
}

// A reading requested before the bracket began is never used: alone, it gives no source.
TEST(IlluminanceSamplerTest, NeverUsesAReadingOlderThanTheBracket) {
  const Clock::time_point start = Clock::now();
  const IlluminanceInstrumentInfo info{.description = "x"};
  const std::vector<IlluminanceReading> stale{
      {.illuminance_lx = 50'000, .requested_at = start - std::chrono::milliseconds(1)}};
  const auto none = summariseReadings(stale, info, start);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("1 stale"), std::string::npos) << none.error().message;
  std::vector<IlluminanceReading> mixed = stale;
  mixed.push_back({.illuminance_lx = 90'000, .requested_at = start});
  const auto fresh = summariseReadings(mixed, info, start);
  ASSERT_TRUE(fresh);
  EXPECT_DOUBLE_EQ(fresh->illuminance_lx, 90'000);
  EXPECT_EQ(fresh->samples, 1);
}

TEST(IlluminanceSamplerTest, ReadsRepeatedlyDuringTheBracket) {
  ScriptedInstrument instrument({90'000.0, 91'000.0, 92'000.0});
  IlluminanceSampler sampler(instrument, std::chrono::milliseconds(5));
  sampler.start();
  while (instrument.reads_ < 3) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const auto source = sampler.stop();
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_GE(*source->samples, 3);
  EXPECT_GT(source->illuminance_lx, 90'000);
  EXPECT_LE(source->illuminance_lx, 92'000);
  EXPECT_GT(*source->spread_lx, 0);
}

TEST(IlluminanceSamplerTest, AShortBracketStillGetsOneReading) {
  ScriptedInstrument instrument({88'000.0});
  IlluminanceSampler sampler(instrument, std::chrono::seconds(10));
  sampler.start();
  const auto source = sampler.stop();  // at once, and without waiting the interval
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_EQ(source->samples, 1);
  EXPECT_DOUBLE_EQ(*source->spread_lx, 0);
}

TEST(IlluminanceSamplerTest, AFailedReadMeansNoSource) {
  ScriptedInstrument instrument({90'000.0, hardwareError("modbus:x: no reply within 500 ms")});
  IlluminanceSampler sampler(instrument, std::chrono::milliseconds(1));
  sampler.start();
  while (instrument.reads_ < 2) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const auto source = sampler.stop();
  ASSERT_FALSE(source);
  EXPECT_NE(source.error().message.find("no reply"), std::string::npos);
}

TEST(IlluminanceSamplerTest, StaleReadingsGiveNoSource) {
  ScriptedInstrument instrument({90'000.0});
  instrument.age = std::chrono::hours(1);  // each answer older than the bracket
  IlluminanceSampler sampler(instrument, std::chrono::milliseconds(1));
  sampler.start();
  const auto source = sampler.stop();
  ASSERT_FALSE(source);
  EXPECT_NE(source.error().message.find("stale"), std::string::npos) << source.error().message;
}

// Each bracket its own: the second does not see the first's readings.
TEST(IlluminanceSamplerTest, ForgetsThePreviousBracket) {
  ScriptedInstrument instrument({hardwareError("first bracket fails"), 90'000.0});
  IlluminanceSampler sampler(instrument, std::chrono::milliseconds(1));
  sampler.start();
  EXPECT_FALSE(sampler.stop());
  sampler.start();
  const auto second = sampler.stop();
  ASSERT_TRUE(second) << second.error().message;
}

#if GLARECAM_WITH_MODBUS
TEST(IlluminanceSamplerTest, SamplesTheSimulatedInstrumentOnLoopback) {
  IlluminanceConfig config = testing::simulatedHeadConfig();
  auto opened = openIlluminance(config, 93'000);
  ASSERT_TRUE(opened) << opened.error().message;
  IlluminanceSampler sampler(*opened->instrument, std::chrono::milliseconds(2));
  sampler.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const auto source = sampler.stop();
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_NEAR(source->illuminance_lx, 93'000, 0.1);
  EXPECT_GE(*source->samples, 2);
  // √(0.02² + (8/93)²) of E: the efficacy dominates.
  EXPECT_NEAR(source->illuminance_u_lx, 93'000 * std::hypot(0.02, 8.0 / 93.0), 1.0);
  // A fault during the next bracket: no source.
  opened->simulator->setFault(SimulatedInstrumentFault::kException);
  sampler.start();
  EXPECT_FALSE(sampler.stop());
}
#endif

}  // namespace
}  // namespace glarecam::rig
