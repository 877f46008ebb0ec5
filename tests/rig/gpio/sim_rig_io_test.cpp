// The simulated GPIO: what it records (LED changes, trigger pulses, with their times), absent
// lines, the scripted button and injected failures.
#include "rig/gpio/sim_rig_io.h"

#include <gtest/gtest.h>

#include <chrono>

#include "rig/gpio/gpio_test_support.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using std::chrono::milliseconds;
using testing::allLines;
using testing::FakeClock;

TEST(SimRigIo, RecordsLedChangesAndTriggerPulsesWithTheirTimes) {
  FakeClock clock;
  const RigClock::time_point t0 = clock.now;
  SimRigIo io(allLines(), clock.function());
  EXPECT_TRUE(io.hasTrigger() && io.hasLed() && io.hasButton());
  EXPECT_EQ(
      io.description(),
      "simulated chip gpiochip0: trigger line 17, LED line 27, button line 'BUTTON', active-low");

  ASSERT_TRUE(io.setLed(false));  // already dark: no change
  clock.now += 10ms;
  ASSERT_TRUE(io.setLed(true));
  clock.now += 5ms;
  ASSERT_TRUE(io.setLed(true));  // no change
  ASSERT_TRUE(io.pulseTrigger());
  clock.now += 20ms;
  ASSERT_TRUE(io.setLed(false));
  ASSERT_TRUE(io.pulseTrigger());

  const auto changes = io.ledChanges();
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(changes[0].at, t0 + 10ms);
  EXPECT_TRUE(changes[0].on);
  EXPECT_EQ(changes[1].at, t0 + 35ms);
  EXPECT_FALSE(changes[1].on);
  EXPECT_FALSE(io.ledOn());
  const auto pulses = io.triggerPulses();
  ASSERT_EQ(pulses.size(), 2u);
  EXPECT_EQ(pulses[0].at, t0 + 15ms);
  EXPECT_EQ(pulses[0].width, 1000us);
  EXPECT_EQ(pulses[1].at, t0 + 35ms);
}

TEST(SimRigIo, AbsentLinesAreNoOps) {
  SimRigIo io(RigIoConfig{});
  EXPECT_FALSE(io.hasTrigger() || io.hasLed() || io.hasButton());
  EXPECT_EQ(io.description(), "simulated chip gpiochip0: no lines");
  EXPECT_TRUE(io.setLed(true));
  EXPECT_TRUE(io.pulseTrigger());
  io.setButtonPressed(true);
  ASSERT_TRUE(io.buttonPressed());
  EXPECT_FALSE(*io.buttonPressed());
  EXPECT_TRUE(io.ledChanges().empty());
  EXPECT_TRUE(io.triggerPulses().empty());
}

TEST(SimRigIo, ButtonFollowsItsScriptAndFailuresAreInjected) {
  FakeClock clock;
  const RigClock::time_point t0 = clock.now;
  SimRigIo io(allLines(), clock.function());
  io.scriptButton({{t0 + 10ms, true}, {t0 + 12ms, false}, {t0 + 20ms, true}});
  const auto levelAt = [&](milliseconds t) {
    clock.now = t0 + t;
    return io.buttonPressed().value();
  };
  EXPECT_FALSE(levelAt(0ms));
  EXPECT_TRUE(levelAt(10ms));
  EXPECT_TRUE(levelAt(11ms));
  EXPECT_FALSE(levelAt(12ms));
  EXPECT_TRUE(levelAt(25ms));
  io.setButtonPressed(false);
  EXPECT_FALSE(levelAt(30ms));

  io.failWith(Error{ErrorCode::kHardware, "line 22 (button) of gpiochip0: gone"});
  const Result<bool> read = io.buttonPressed();
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().message, "line 22 (button) of gpiochip0: gone");
  EXPECT_FALSE(io.setLed(true));
  EXPECT_FALSE(io.pulseTrigger());
  io.failWith(std::nullopt);
  EXPECT_TRUE(io.setLed(true));
}

}  // namespace
}  // namespace glarecam::rig
