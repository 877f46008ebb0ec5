// The status LED: blink codes at exact times, StatusLed's ticks on simulated time, a changed
// status restarting its pattern, failed writes retried, and its thread's start and shutdown.
#include "rig/gpio/status_led.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <utility>
#include <vector>

#include "rig/gpio/gpio_test_support.h"
#include "rig/gpio/sim_rig_io.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using std::chrono::milliseconds;
using testing::allLines;
using testing::FakeClock;

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

}  // namespace
}  // namespace glarecam::rig
