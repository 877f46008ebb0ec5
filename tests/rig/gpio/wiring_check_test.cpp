// `glarecam gpio`'s wiring checks: the LED states by name, each check refused without its line on
// the simulated chip "sim", and each check driving its line: an LED pattern, spaced trigger
// pulses, a button press within the timeout.
#include "rig/gpio/wiring_check.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>

#include "rig/gpio/gpio_test_support.h"
#include "rig/gpio/rig_io_registry.h"
#include "rig/gpio/sim_rig_io.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using testing::allLines;

TEST(WiringCheck, LedStatesAreParsedByName) {
  EXPECT_EQ(parseRigState("ready"), RigState::ready());
  EXPECT_EQ(parseRigState("capturing"), RigState::capturing());
  for (const FaultCode code :
       {FaultCode::kCamera, FaultCode::kInclinometer, FaultCode::kDisk, FaultCode::kClock}) {
    EXPECT_EQ(parseRigState("fault-" + std::string(faultName(code))), RigState::faulted(code));
  }
  for (const char* unknown : {"", "Ready", "fault", "fault-", "fault-smoke", "blink"}) {
    const auto parsed = parseRigState(unknown);
    ASSERT_FALSE(parsed) << unknown;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput);
    EXPECT_EQ(parsed.error().message,
              "gpio: --led " + std::string(unknown) +
                  " is unknown (known: ready, capturing, fault-camera, fault-inclinometer, "
                  "fault-disk, fault-clock)");
  }
}

TEST(WiringCheck, EachCheckNeedsItsLine) {
  RigIoConfig config;
  config.chip = "sim";
  auto io = openRigIo(config);  // the simulated chip, no lines
  ASSERT_TRUE(io) << io.error().message;
  const Status led = showLedPattern(**io, RigState::ready(), 10ms);
  ASSERT_FALSE(led);
  EXPECT_EQ(led.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(led.error().message, "gpio: --led, but the config's [gpio] has no led line");
  const Status trigger = pulseTriggers(**io, 1);
  ASSERT_FALSE(trigger);
  EXPECT_EQ(trigger.error().message,
            "gpio: --trigger, but the config's [gpio] has no trigger line");
  const auto button = waitForButtonWithin(**io, 30ms, 10ms);
  ASSERT_FALSE(button);
  EXPECT_EQ(button.error().message,
            "gpio: --wait-button, but the config's [gpio] has no button line");
}

TEST(WiringCheck, TriggerPulsesAreSpacedForAScope) {
  SimRigIo io(allLines());
  ASSERT_TRUE(pulseTriggers(io, 3));
  const auto pulses = io.triggerPulses();
  ASSERT_EQ(pulses.size(), 3u);
  // At least the spacing apart (a loaded machine may be slower, never faster).
  EXPECT_GE(pulses[1].at - pulses[0].at, kTriggerSpacing);
  EXPECT_GE(pulses[2].at - pulses[1].at, kTriggerSpacing);
  ASSERT_TRUE(pulseTriggers(io, 0));
  EXPECT_EQ(io.triggerPulses().size(), 3u);
}

TEST(WiringCheck, ALedPatternPlaysAndLeavesTheLedDark) {
  SimRigIo io(allLines());
  ASSERT_TRUE(showLedPattern(io, RigState::capturing(), 300ms));
  const auto changes = io.ledChanges();
  ASSERT_GE(changes.size(), 2u);
  EXPECT_TRUE(changes.front().on);  // capturing starts lit
  EXPECT_FALSE(changes.back().on);
  EXPECT_FALSE(io.ledOn());
  io.failWith(Error{ErrorCode::kHardware, "line 27 (LED) of gpiochip0: cannot set"});
  const Status failed = showLedPattern(io, RigState::ready(), 50ms);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().message, "line 27 (LED) of gpiochip0: cannot set");
}

TEST(WiringCheck, AButtonPressIsSeenWithinTheTimeout) {
  // The button's script runs on a clock of its own that moves a millisecond at each read: the
  // first 10 reads see it released, then it is pressed and held. So the wait sees the press begin
  // however late a loaded machine starts it (a button already held when the wait begins is no
  // press); in real time on a 50 ms script it once started after the press, and waited out 10 s.
  const RigClock::time_point t0{};
  auto reads = std::make_shared<int>(0);
  SimRigIo io(allLines(), [t0, reads] { return t0 + std::chrono::milliseconds(++*reads); });
  io.scriptButton({{t0 + 11ms, true}});
  const RigClock::time_point now = RigClock::now();
  const auto pressed = waitForButtonWithin(io, 20ms, 10s);
  ASSERT_TRUE(pressed) << pressed.error().message;
  EXPECT_TRUE(*pressed);
  EXPECT_GT(io.buttonReads(), 10);         // released first, then pressed
  EXPECT_GE(RigClock::now() - now, 20ms);  // held through the debounce

  SimRigIo idle(allLines());
  const auto start = RigClock::now();
  const auto timed_out = waitForButtonWithin(idle, 20ms, 200ms);
  ASSERT_TRUE(timed_out) << timed_out.error().message;
  EXPECT_FALSE(*timed_out);
  EXPECT_GE(RigClock::now() - start, 200ms);
}

}  // namespace
}  // namespace glarecam::rig
