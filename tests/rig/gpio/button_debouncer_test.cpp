// The button: the debouncer on simulated time (bounces, glitches, a button held from the start)
// and the watcher polling it until a press, a deadline or a stop request.
#include "rig/gpio/button_debouncer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stop_token>
#include <tuple>
#include <vector>

#include "rig/gpio/gpio_test_support.h"
#include "rig/gpio/sim_rig_io.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using std::chrono::milliseconds;
using testing::allLines;
using testing::FakeClock;

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

}  // namespace
}  // namespace glarecam::rig
