// The rig's GPIO: blink codes at exact times, the debouncer and the button watcher on simulated
// time (no sleeping, no timing asserted on the real clock), the simulator's records, StatusLed's
// ticks and shutdown, config validation, the backend's messages, and the libgpiod backend's
// error paths against the real library on a machine without GPIO chips.
#include "rig/gpio/rig_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stop_token>
#include <thread>

#include "rig/gpio/button_debouncer.h"
#include "rig/gpio/gpio_errors.h"
#include "rig/gpio/rig_io_registry.h"
#include "rig/gpio/sim_rig_io.h"
#include "rig/gpio/status_led.h"
#include "support/test_support.h"
#include "core/build_config.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using std::chrono::milliseconds;

// Simulated time: the tests advance it; nothing here sleeps on it.
struct FakeClock {
  RigClock::time_point now = RigClock::time_point(1000s);  // any origin
  RigClockFunction function() {
    return [this] { return now; };
  }
};

RigIoConfig allLines() {
  RigIoConfig config;
  config.trigger = GpioLine{17u};
  config.led = GpioLine{27u};
  config.button = GpioLine{std::string("BUTTON"), true};
  return config;
}

// ---------------------------------------------------------------- blink codes

TEST(BlinkCodes, ReadyIsAHeartbeat) {
  const RigState ready = RigState::ready();
  EXPECT_EQ(patternPeriod(ready), 2000ms);
  EXPECT_TRUE(ledLevelAt(ready, 0ms));
  EXPECT_TRUE(ledLevelAt(ready, 1899ms));
  EXPECT_FALSE(ledLevelAt(ready, 1900ms));
  EXPECT_FALSE(ledLevelAt(ready, 1999ms));
  EXPECT_TRUE(ledLevelAt(ready, 2000ms));
  EXPECT_FALSE(ledLevelAt(ready, 3999ms));
  EXPECT_TRUE(ledLevelAt(ready, -5ms));  // before the start: the start
}

TEST(BlinkCodes, CapturingBlinksAtFiveHertz) {
  const RigState capturing = RigState::capturing();
  EXPECT_EQ(patternPeriod(capturing), 200ms);
  EXPECT_TRUE(ledLevelAt(capturing, 0ms));
  EXPECT_TRUE(ledLevelAt(capturing, 99ms));
  EXPECT_FALSE(ledLevelAt(capturing, 100ms));
  EXPECT_FALSE(ledLevelAt(capturing, 199ms));
  EXPECT_TRUE(ledLevelAt(capturing, 200ms));
  EXPECT_FALSE(ledLevelAt(capturing, 1'000'300ms));
}

TEST(BlinkCodes, FaultNIsNShortBlinksThenAPause) {
  for (const FaultCode fault :
       {FaultCode::kCamera, FaultCode::kInclinometer, FaultCode::kDisk, FaultCode::kClock}) {
    SCOPED_TRACE(faultName(fault));
    const RigState state = RigState::faulted(fault);
    const int blinks = static_cast<int>(fault);
    const milliseconds period = patternPeriod(state);
    EXPECT_EQ(period, blinks * 500ms + 1500ms);
    // Walk one period millisecond by millisecond: lit exactly in [500 i, 500 i + 200).
    int rising_edges = 0;
    bool previous = false;
    for (milliseconds t = 0ms; t < period; t += 1ms) {
      const bool lit = ledLevelAt(state, t);
      const bool expected = t < blinks * 500ms && t % 500ms < 200ms;
      ASSERT_EQ(lit, expected) << "at " << t.count() << " ms";
      if (lit && !previous) ++rising_edges;
      previous = lit;
    }
    EXPECT_EQ(rising_edges, blinks);
    // The pause: dark from the end of the last blink to the end of the period, then it repeats.
    EXPECT_FALSE(ledLevelAt(state, (blinks - 1) * 500ms + 200ms));
    EXPECT_FALSE(ledLevelAt(state, period - 1ms));
    EXPECT_TRUE(ledLevelAt(state, period));
    EXPECT_TRUE(ledLevelAt(state, 7 * period + 150ms));
  }
}

TEST(BlinkCodes, FaultCodesAreNamedAndCompared) {
  EXPECT_EQ(faultName(FaultCode::kCamera), "camera");
  EXPECT_EQ(faultName(FaultCode::kInclinometer), "inclinometer");
  EXPECT_EQ(faultName(FaultCode::kDisk), "disk");
  EXPECT_EQ(faultName(FaultCode::kClock), "clock");
  EXPECT_EQ(RigState::faulted(FaultCode::kDisk), RigState::faulted(FaultCode::kDisk));
  EXPECT_NE(RigState::faulted(FaultCode::kDisk), RigState::faulted(FaultCode::kClock));
  EXPECT_EQ(RigState::ready(), (RigState{RigStatus::kReady, FaultCode::kDisk}));  // code ignored
  EXPECT_NE(RigState::ready(), RigState::capturing());
}

// ---------------------------------------------------------------- debouncer

// Feeds `level` every millisecond over [from, to); the times at which a press was reported.
std::vector<milliseconds> feed(ButtonDebouncer& debouncer, bool level, milliseconds from,
                               milliseconds to) {
  std::vector<milliseconds> presses;
  for (milliseconds t = from; t < to; t += 1ms) {
    if (debouncer.update(level, RigClock::time_point(t))) presses.push_back(t);
  }
  return presses;
}

TEST(ButtonDebouncer, ReportsACleanPressOnceAfterTheDebounceTime) {
  ButtonDebouncer debouncer(50ms);
  EXPECT_TRUE(feed(debouncer, false, 0ms, 100ms).empty());
  EXPECT_EQ(feed(debouncer, true, 100ms, 400ms), std::vector<milliseconds>{150ms});
  EXPECT_TRUE(debouncer.pressed());
  EXPECT_TRUE(feed(debouncer, false, 400ms, 500ms).empty());
  EXPECT_FALSE(debouncer.pressed());
  EXPECT_EQ(feed(debouncer, true, 500ms, 600ms), std::vector<milliseconds>{550ms});
}

TEST(ButtonDebouncer, IgnoresBouncesAndCountsFromTheLastEdge) {
  ButtonDebouncer debouncer(50ms);
  std::vector<milliseconds> presses = feed(debouncer, false, 0ms, 100ms);
  // Contact closing: 2-4 ms bounces, then closed from 112 ms.
  for (const auto& [level, from, to] : std::vector<std::tuple<bool, milliseconds, milliseconds>>{
           {true, 100ms, 102ms},
           {false, 102ms, 105ms},
           {true, 105ms, 109ms},
           {false, 109ms, 112ms},
           {true, 112ms, 300ms},
           // Contact opening, bouncing back to "pressed" for 3 ms: no second press.
           {false, 300ms, 303ms},
           {true, 303ms, 306ms},
           {false, 306ms, 400ms}}) {
    for (milliseconds t : feed(debouncer, level, from, to)) presses.push_back(t);
  }
  EXPECT_EQ(presses, std::vector<milliseconds>{162ms});
}

TEST(ButtonDebouncer, APressShorterThanTheDebounceIsNoPress) {
  ButtonDebouncer debouncer(50ms);
  EXPECT_TRUE(feed(debouncer, false, 0ms, 100ms).empty());
  EXPECT_TRUE(feed(debouncer, true, 100ms, 149ms).empty());  // 49 ms
  EXPECT_TRUE(feed(debouncer, false, 149ms, 300ms).empty());
}

TEST(ButtonDebouncer, ReleaseGlitchDuringAHoldIsNoSecondPress) {
  ButtonDebouncer debouncer(50ms);
  feed(debouncer, false, 0ms, 100ms);
  EXPECT_EQ(feed(debouncer, true, 100ms, 300ms).size(), 1u);
  EXPECT_TRUE(feed(debouncer, false, 300ms, 340ms).empty());  // released 40 ms: a bounce
  EXPECT_TRUE(feed(debouncer, true, 340ms, 600ms).empty());
}

TEST(ButtonDebouncer, AButtonHeldFromTheStartMustBeReleasedFirst) {
  ButtonDebouncer debouncer(50ms);
  EXPECT_TRUE(feed(debouncer, true, 0ms, 1000ms).empty());
  EXPECT_TRUE(debouncer.pressed());  // the level is pressed, but no press was reported
  EXPECT_TRUE(feed(debouncer, false, 1000ms, 1030ms).empty());  // released too briefly
  EXPECT_TRUE(feed(debouncer, true, 1030ms, 1200ms).empty());
  EXPECT_TRUE(feed(debouncer, false, 1200ms, 1300ms).empty());
  EXPECT_EQ(feed(debouncer, true, 1300ms, 1400ms), std::vector<milliseconds>{1350ms});
}

TEST(ButtonDebouncer, ZeroDebounceReportsEveryEdge) {
  ButtonDebouncer debouncer(0ms);
  EXPECT_FALSE(debouncer.update(false, RigClock::time_point(0ms)));
  EXPECT_TRUE(debouncer.update(true, RigClock::time_point(1ms)));
  EXPECT_FALSE(debouncer.update(true, RigClock::time_point(2ms)));
  EXPECT_FALSE(debouncer.update(false, RigClock::time_point(3ms)));
  EXPECT_TRUE(debouncer.update(true, RigClock::time_point(4ms)));
}

TEST(ButtonDebouncer, SparseSamplesCountFromTheFirstSampleOfTheNewLevel) {
  ButtonDebouncer debouncer(50ms);
  EXPECT_FALSE(debouncer.update(false, RigClock::time_point(0ms)));
  EXPECT_FALSE(debouncer.update(false, RigClock::time_point(60ms)));
  EXPECT_FALSE(debouncer.update(true, RigClock::time_point(100ms)));  // closed since ≤ 100 ms
  EXPECT_FALSE(debouncer.update(true, RigClock::time_point(149ms)));
  EXPECT_TRUE(debouncer.update(true, RigClock::time_point(150ms)));
}

// ---------------------------------------------------------------- simulator

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

// ---------------------------------------------------------------- status LED

// The LED's changes as (milliseconds since t0, level).
std::vector<std::pair<milliseconds, bool>> changesSince(const SimRigIo& io,
                                                        RigClock::time_point t0) {
  std::vector<std::pair<milliseconds, bool>> changes;
  for (const auto& change : io.ledChanges()) {
    changes.emplace_back(std::chrono::duration_cast<milliseconds>(change.at - t0), change.on);
  }
  return changes;
}

// Ticks every 10 ms over [now, now + duration), as the thread would.
void tickFor(StatusLed& led, FakeClock& clock, milliseconds duration) {
  const RigClock::time_point end = clock.now + duration;
  for (; clock.now < end; clock.now += kStatusLedTick) ASSERT_TRUE(led.tick(clock.now));
}

TEST(StatusLed, TicksPlayTheReadyHeartbeat) {
  FakeClock clock;
  const RigClock::time_point t0 = clock.now;
  SimRigIo io(allLines(), clock.function());
  StatusLed led(io, clock.function());
  tickFor(led, clock, 4100ms);
  using Changes = std::vector<std::pair<milliseconds, bool>>;
  EXPECT_EQ(
      changesSince(io, t0),
      (Changes{{0ms, true}, {1900ms, false}, {2000ms, true}, {3900ms, false}, {4000ms, true}}));
}

TEST(StatusLed, AChangedStatusRestartsItsPattern) {
  FakeClock clock;
  const RigClock::time_point t0 = clock.now;
  SimRigIo io(allLines(), clock.function());
  StatusLed led(io, clock.function());
  tickFor(led, clock, 50ms);
  led.setStatus(RigState::capturing());  // at 50 ms: lit already, so no write until 150 ms
  tickFor(led, clock, 450ms);
  led.setStatus(RigState::capturing());  // the same: no restart (at 500 ms, mid-blink)
  tickFor(led, clock, 50ms);
  led.setStatus(RigState::faulted(FaultCode::kDisk));  // at 550 ms
  tickFor(led, clock, 4010ms);
  EXPECT_EQ(led.status(), RigState::faulted(FaultCode::kDisk));

  using Changes = std::vector<std::pair<milliseconds, bool>>;
  const Changes changes = changesSince(io, t0);
  // Capturing from 50 ms: dark at 150, lit at 250, dark at 350, lit at 450; at 550 the fault
  // pattern starts lit (the LED was lit since 450: no write). Disk = 4 blinks from 550 ms:
  // lit [550, 750), [1050, 1250), [1550, 1750), [2050, 2250), pause to 550 + 3500 = 4050.
  const Changes want{{0ms, true},    {150ms, false},  {250ms, true},  {350ms, false},
                     {450ms, true},  {750ms, false},  {1050ms, true}, {1250ms, false},
                     {1550ms, true}, {1750ms, false}, {2050ms, true}, {2250ms, false},
                     {4050ms, true}, {4250ms, false}, {4550ms, true}};
  EXPECT_EQ(changes, want);
}

TEST(StatusLed, AFailedWriteIsKeptAndRetried) {
  FakeClock clock;
  SimRigIo io(allLines(), clock.function());
  StatusLed led(io, clock.function());
  io.failWith(Error{ErrorCode::kHardware, "line 27 (LED) of gpiochip0: cannot set"});
  const Status first = led.tick(clock.now);
  ASSERT_FALSE(first);
  ASSERT_TRUE(led.lastError().has_value());
  EXPECT_EQ(led.lastError()->message, "line 27 (LED) of gpiochip0: cannot set");
  io.failWith(std::nullopt);
  clock.now += kStatusLedTick;
  EXPECT_TRUE(led.tick(clock.now));  // retried although the level did not change
  EXPECT_TRUE(io.ledOn());
}

TEST(StatusLed, StopDarkensTheLedAndLaterTicksDoNothing) {
  FakeClock clock;
  SimRigIo io(allLines(), clock.function());
  StatusLed led(io, clock.function());
  ASSERT_TRUE(led.tick(clock.now));
  EXPECT_TRUE(io.ledOn());
  EXPECT_TRUE(led.stop());
  EXPECT_FALSE(io.ledOn());
  clock.now += 100ms;
  EXPECT_TRUE(led.tick(clock.now));
  EXPECT_FALSE(io.ledOn());
  EXPECT_TRUE(led.stop());  // idempotent
  EXPECT_EQ(io.ledChanges().size(), 2u);
}

TEST(StatusLed, WithoutALedEverythingIsANoOp) {
  SimRigIo io(RigIoConfig{});
  StatusLed led(io);
  EXPECT_TRUE(led.tick(RigClock::now()));
  EXPECT_TRUE(led.stop());
}

// The thread on the real clock: only that it writes, takes status changes from another thread,
// and leaves the LED dark when destroyed; no timing is asserted.
TEST(StatusLed, ThreadDrivesTheLedAndShutsDownCleanly) {
  SimRigIo io(allLines());
  {
    StatusLed led(io);
    led.start();
    led.start();  // already running: no second thread
    // Waits (bounded, generously for a loaded machine) for the thread's first write.
    const auto give_up = RigClock::now() + 10s;
    while (io.ledChanges().empty() && RigClock::now() < give_up) std::this_thread::sleep_for(1ms);
    ASSERT_FALSE(io.ledChanges().empty());
    EXPECT_TRUE(io.ledChanges().front().on);
    std::jthread other([&led] {
      led.setStatus(RigState::capturing());
      led.setStatus(RigState::faulted(FaultCode::kCamera));
    });
    other.join();
    EXPECT_EQ(led.status(), RigState::faulted(FaultCode::kCamera));
  }
  const auto changes = io.ledChanges();
  ASSERT_FALSE(changes.empty());
  EXPECT_FALSE(changes.back().on);
  EXPECT_FALSE(io.ledOn());
  std::this_thread::sleep_for(3 * kStatusLedTick);
  EXPECT_EQ(io.ledChanges().size(), changes.size());  // the thread is gone
}

TEST(StatusLed, RestartsAfterStop) {
  SimRigIo io(allLines());
  StatusLed led(io);
  led.start();
  EXPECT_TRUE(led.stop());
  const std::size_t after_stop = io.ledChanges().size();
  led.start();
  const auto give_up = RigClock::now() + 10s;
  while (io.ledChanges().size() == after_stop && RigClock::now() < give_up) {
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_TRUE(io.ledChanges().back().on);
  EXPECT_TRUE(led.stop());
  EXPECT_FALSE(io.ledOn());
}

// ---------------------------------------------------------------- button watcher

// A watcher on simulated time: every sleep advances the clock.
struct WatchedButton {
  FakeClock clock;
  RigClock::time_point t0 = clock.now;
  SimRigIo io{allLines(), clock.function()};
  int sleeps = 0;
  ButtonWatcher watcher{io, 50ms, clock.function(), [this](RigClock::duration duration) {
                          EXPECT_LE(duration, kButtonPollPeriod);
                          ++sleeps;
                          clock.now += duration;
                        }};
};

TEST(ButtonWatcher, ReportsABouncyPressOnceDebounced) {
  WatchedButton button;
  const RigClock::time_point t0 = button.t0;
  // Polls at 0, 5, 10, ... ms. Bounces between 100 and 120 ms, closed from 120 ms to 400 ms.
  button.io.scriptButton({{t0 + 100ms, true},
                          {t0 + 103ms, false},
                          {t0 + 107ms, true},
                          {t0 + 112ms, false},
                          {t0 + 120ms, true},
                          {t0 + 400ms, false}});
  const Result<bool> pressed = button.watcher.waitForPress(t0 + 10s);
  ASSERT_TRUE(pressed) << pressed.error().message;
  EXPECT_TRUE(*pressed);
  // The sample at 120 ms is the first of the closed contact: a press 50 ms later.
  EXPECT_EQ(button.clock.now - t0, 170ms);
  EXPECT_EQ(button.io.buttonReads(), 35);  // 0, 5, ..., 170 ms
}

TEST(ButtonWatcher, ReturnsFalseAtTheDeadline) {
  WatchedButton button;
  button.io.scriptButton({{button.t0 + 100ms, true}, {button.t0 + 130ms, false}});  // too short
  const Result<bool> pressed = button.watcher.waitForPress(button.t0 + 1003ms);
  ASSERT_TRUE(pressed);
  EXPECT_FALSE(*pressed);
  EXPECT_EQ(button.clock.now, button.t0 + 1003ms);  // the last sleep shortened to the deadline
}

TEST(ButtonWatcher, AButtonHeldWhenWatchingBeginsIsNoPress) {
  WatchedButton button;
  button.io.setButtonPressed(true);
  const Result<bool> held = button.watcher.waitForPress(button.t0 + 1s);
  ASSERT_TRUE(held);
  EXPECT_FALSE(*held);
  // Released and pressed again during the next wait: a press.
  const RigClock::time_point t1 = button.clock.now;
  button.io.scriptButton({{t1, true}, {t1 + 20ms, false}, {t1 + 200ms, true}});
  const Result<bool> pressed = button.watcher.waitForPress(t1 + 1s);
  ASSERT_TRUE(pressed);
  EXPECT_TRUE(*pressed);
  EXPECT_EQ(button.clock.now - t1, 250ms);
}

TEST(ButtonWatcher, StopsOnRequest) {
  WatchedButton button;
  std::stop_source stop;
  stop.request_stop();
  const Result<bool> stopped = button.watcher.waitForPress(button.t0 + 1s, stop.get_token());
  ASSERT_TRUE(stopped);
  EXPECT_FALSE(*stopped);
  EXPECT_EQ(button.io.buttonReads(), 0);

  // A stop requested while polling is seen at the next poll.
  std::stop_source later;
  ButtonWatcher watcher(button.io, 50ms, button.clock.function(), [&](RigClock::duration duration) {
    button.clock.now += duration;
    if (button.clock.now - button.t0 >= 20ms) later.request_stop();
  });
  const Result<bool> interrupted = watcher.waitForPress(button.t0 + 1s, later.get_token());
  ASSERT_TRUE(interrupted);
  EXPECT_FALSE(*interrupted);
  EXPECT_EQ(button.clock.now - button.t0, 20ms);
}

TEST(ButtonWatcher, FailsWithoutAButtonOrWhenTheReadFails) {
  SimRigIo none(RigIoConfig{});
  ButtonWatcher without(none, 50ms);
  const Result<bool> missing = without.waitForPress(RigClock::now() + 1s);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::kBadInput);

  WatchedButton button;
  button.io.failWith(Error{ErrorCode::kHardware, "line 22 (button) of gpiochip0: gone"});
  const Result<bool> failed = button.watcher.waitForPress(button.t0 + 1s);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().code, ErrorCode::kHardware);
  EXPECT_EQ(failed.error().message, "line 22 (button) of gpiochip0: gone");
}

// ---------------------------------------------------------------- config

TEST(RigIoConfig, ValidatesItsFields) {
  EXPECT_TRUE(RigIoConfig{}.validate());
  EXPECT_TRUE(allLines().validate());

  const auto problem = [](const RigIoConfig& config) {
    const Status status = config.validate();
    EXPECT_FALSE(status);
    if (status) return std::string();
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
    return status.error().message;
  };
  RigIoConfig config = allLines();
  config.chip = "";
  EXPECT_EQ(problem(config), "GPIO chip: empty (a name such as gpiochip0, a path or label)");

  config = allLines();
  config.led = GpioLine{std::string()};
  EXPECT_EQ(problem(config), "GPIO LED line: empty name (give an offset or a name from gpioinfo)");

  config = allLines();
  config.button = GpioLine{17u, true};
  EXPECT_EQ(problem(config), "GPIO trigger and button are the same line 17, active-low");
  config = allLines();
  config.led = GpioLine{std::string("BUTTON")};
  EXPECT_EQ(problem(config), "GPIO LED and button are the same line 'BUTTON', active-low");

  config = allLines();
  config.debounce = -1ms;
  EXPECT_EQ(problem(config), "GPIO button debounce -1 ms: outside 0..1000 ms");
  config.debounce = 1001ms;
  EXPECT_EQ(problem(config), "GPIO button debounce 1001 ms: outside 0..1000 ms");
  config.debounce = 0ms;
  EXPECT_TRUE(config.validate());

  config.trigger_pulse = 0us;
  EXPECT_EQ(problem(config), "GPIO trigger pulse 0 us: outside 1..100000 us");
  config.trigger_pulse = 100'001us;
  EXPECT_EQ(problem(config), "GPIO trigger pulse 100001 us: outside 1..100000 us");
}

TEST(RigIoConfig, DescribesLines) {
  EXPECT_EQ(describeGpioLine(GpioLine{17u}), "line 17");
  EXPECT_EQ(describeGpioLine(GpioLine{std::string("STATUS_LED"), true}),
            "line 'STATUS_LED', active-low");
}

// ---------------------------------------------------------------- backend messages

TEST(GpioErrors, NameTheChipAndLineAndSayWhatToDo) {
  EXPECT_EQ(gpioChipOpenError("gpiochip0", ENOENT, {}).message,
            "GPIO chip gpiochip0 not found (/dev/gpiochip* present: none)");
  EXPECT_EQ(
      gpioChipOpenError("gpiochip4", ENOENT, {"gpiochip0 [pinctrl-bcm2711]", "gpiochip1"}).message,
      "GPIO chip gpiochip4 not found (/dev/gpiochip* present: gpiochip0 [pinctrl-bcm2711], "
      "gpiochip1)");
  EXPECT_EQ(gpioChipOpenError("/dev/null", ENOTTY, {}).message,
            "/dev/null is not a GPIO chip (/dev/gpiochip* present: none)");
  const Error denied = gpioChipOpenError("gpiochip0", EACCES, {});
  EXPECT_EQ(denied.code, ErrorCode::kHardware);
  EXPECT_NE(denied.message.find("permission denied"), std::string::npos);
  EXPECT_NE(denied.message.find("gpio group"), std::string::npos);
  EXPECT_NE(denied.message.find("udev rule"), std::string::npos);

  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 17 (LED)", EBUSY, "gpio-leds").message,
            "line 17 (LED) of gpiochip0 is used by gpio-leds");
  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 17 (LED)", EBUSY, "").message,
            "line 17 (LED) of gpiochip0 is used by another program or a kernel driver");
  EXPECT_NE(
      gpioLineRequestError("gpiochip0", "line 22 (button)", EPERM, "").message.find("gpio group"),
      std::string::npos);
  const std::string bias =
      gpioLineRequestError("gpiochip0", "line 22 (button)", EINVAL, "", true).message;
  EXPECT_NE(bias.find("button_pull_up = false"), std::string::npos) << bias;
  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 22 (button)", EINVAL, "", false).message,
            "line 22 (button) of gpiochip0: Invalid argument");
}

TEST(RigIoConfig, APulledUpButtonMustBeActiveLow) {
  RigIoConfig config;
  config.button = GpioLine{22u, false};  // the pull-up holds it high: it would read pressed
  const Status refused = config.validate();
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("button_active_low = true"), std::string::npos);
  config.button->active_low = true;
  EXPECT_TRUE(config.validate());
  config.button->active_low = false;
  config.button_pull_up = false;  // an external pull-down, a button to 3.3 V
  EXPECT_TRUE(config.validate());
}

// The simulated chip checks lines as a Raspberry Pi 4's gpiochip0 would (58 lines, GPIOn).
TEST(SimChip, ChecksLinesLikeARealChip) {
  RigIoConfig config;
  config.chip = "sim";
  config.led = GpioLine{17u, false};
  config.trigger = GpioLine{std::string("GPIO22"), false};
  ASSERT_TRUE(openRigIo(config));
  config.trigger = GpioLine{std::string("GPIO17"), false};  // the LED's line by name
  EXPECT_EQ(openRigIo(config).error().code, ErrorCode::kBadInput);
  config.trigger = GpioLine{58u, false};
  const auto beyond = openRigIo(config);
  ASSERT_FALSE(beyond);
  EXPECT_NE(beyond.error().message.find("beyond the simulated chip's 58 lines"), std::string::npos);
  config.trigger = GpioLine{std::string("GPIO022"), false};  // no such name on a real chip
  EXPECT_FALSE(openRigIo(config));
  config.trigger = GpioLine{std::string("STATUS"), false};
  EXPECT_NE(openRigIo(config).error().message.find("'STATUS' (trigger) not found"),
            std::string::npos);
}

TEST(SimChip, ScriptedPressesOutlastTheDebounce) {
  RigIoConfig config;
  config.chip = "sim:button_period_s=0.5";
  config.button = GpioLine{27u, true};
  config.debounce = std::chrono::milliseconds(300);  // presses of 600 ms do not fit in 0.5 s
  const auto refused = openRigIo(config);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("too short for debounce_ms = 300"), std::string::npos);
  config.chip = "sim:button_period_s=2";
  EXPECT_TRUE(openRigIo(config));
  config.chip = "sim:wobble=1";
  EXPECT_EQ(openRigIo(config).error().code, ErrorCode::kBadInput);
}

TEST(GpioErrors, ListsPresentChipsSorted) {
  testing::TempDir dev;
  for (const char* name : {"gpiochip1", "ttyS0", "gpiochip0"}) std::ofstream(dev.path() / name);
  EXPECT_EQ(presentGpioChips(dev.path()), (std::vector<std::string>{"gpiochip0", "gpiochip1"}));
  EXPECT_TRUE(presentGpioChips(dev.path() / "absent").empty());
}

// ---------------------------------------------------------------- the real library

#if GLARECAM_WITH_GPIOD

// Messages list the machine's chips: exact only where there are none.
bool machineHasGpioChips() { return !presentGpioChips().empty(); }

TEST(GpiodRigIo, AnAbsentChipIsNamed) {
  if (std::filesystem::exists("/dev/gpiochip0")) GTEST_SKIP() << "this machine has gpiochip0";
  const auto io = openGpiodRigIo(allLines());
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  if (!machineHasGpioChips()) {
    EXPECT_EQ(io.error().message, "GPIO chip gpiochip0 not found (/dev/gpiochip* present: none)");
  }
  for (const char* chip : {"/dev/gpiochip0", "0", "no-such-label"}) {
    RigIoConfig config = allLines();
    config.chip = chip;
    const auto absent = openGpiodRigIo(config);
    ASSERT_FALSE(absent) << chip;
    EXPECT_EQ(absent.error().code, ErrorCode::kHardware);
    EXPECT_TRUE(absent.error().message.starts_with("GPIO chip " + std::string(chip) +
                                                   " not found (/dev/gpiochip* present: "))
        << absent.error().message;
  }
}

TEST(GpiodRigIo, AFileThatIsNoChipIsRefused) {
  testing::TempDir directory;
  const std::filesystem::path file = directory.path() / "gpiochip0";
  std::ofstream(file) << "not a chip\n";
  for (const std::string& chip :
       {std::string("/dev/null"), file.string(), directory.path().string()}) {
    RigIoConfig config = allLines();
    config.chip = chip;
    const auto io = openGpiodRigIo(config);
    ASSERT_FALSE(io) << chip;
    EXPECT_EQ(io.error().code, ErrorCode::kHardware);
    EXPECT_TRUE(io.error().message.starts_with(chip + " is not a GPIO chip ("))
        << io.error().message;
  }
}

TEST(GpiodRigIo, AnInvalidConfigFailsBeforeTouchingTheHardware) {
  RigIoConfig config = allLines();
  config.trigger_pulse = 0us;
  const auto io = openGpiodRigIo(config);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kBadInput);
}

TEST(GpiodRigIo, OpensARealChipWhenThereIsOne) {
  if (!std::filesystem::exists("/dev/gpiochip0")) GTEST_SKIP() << "no /dev/gpiochip0 here";
  RigIoConfig config;  // no lines: opening the chip claims nothing
  const auto io = openGpiodRigIo(config);
  ASSERT_TRUE(io) << io.error().message;
  EXPECT_TRUE((*io)->description().starts_with("gpiochip0 ["));
  EXPECT_FALSE((*io)->hasLed());
  EXPECT_TRUE((*io)->setLed(true));
}

#else

TEST(GpiodRigIo, SaysItWasBuiltWithoutLibgpiod) {
  const auto io = openGpiodRigIo(allLines());
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  EXPECT_NE(io.error().message.find("glarecam was built without libgpiod"), std::string::npos);
}

#endif

}  // namespace
}  // namespace glarecam::rig
