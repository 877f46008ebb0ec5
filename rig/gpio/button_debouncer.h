// The operator button, debounced. A mechanical contact bounces for a few milliseconds when it
// closes and opens; a press counts once the level has been stable "pressed" for the debounce time,
// and the next press only after the level has been stable "released" as long. The level at the
// start is unknown until it has been stable: a button already held (or stuck) when watching
// begins is not a press; it must be released and pressed again.
//
// ButtonDebouncer is the pure rule over (level, time) samples. ButtonWatcher polls a RigIo's
// button through it every kButtonPollPeriod until a press, a deadline or a stop request; its clock
// and sleep are injectable so that tests run on simulated time.
#pragma once

#include <chrono>
#include <functional>
#include <stop_token>

#include "rig/gpio/rig_io.h"

namespace glarecam::rig {

// How often ButtonWatcher reads the button: a press is reported at most this late after its
// debounce time has passed, and a stop request is seen at most this late.
inline constexpr std::chrono::milliseconds kButtonPollPeriod{5};

class ButtonDebouncer {
 public:
  explicit ButtonDebouncer(std::chrono::nanoseconds debounce);

  // Feeds the level read at `at` (true = pressed; times non-decreasing). True exactly once per
  // press: at the first sample at which the level has read "pressed" for `debounce` since it
  // last changed, after a stable release. A level that changes back sooner is a bounce, ignored.
  bool update(bool pressed, RigClock::time_point at);

  // The debounced level: true while the button is stably pressed, including a hold from the start
  // that update() did not report; false while the level is unknown.
  bool pressed() const { return stable_ == Level::kPressed; }

 private:
  enum class Level { kUnknown, kReleased, kPressed };

  std::chrono::nanoseconds debounce_;
  Level stable_ = Level::kUnknown;  // until the first level has been stable
  Level raw_ = Level::kUnknown;     // the last sample's level
  RigClock::time_point raw_since_;  // when the samples first read raw_
};

class ButtonWatcher {
 public:
  using SleepFunction = std::function<void(RigClock::duration)>;

  // `io` must outlive this. The default sleep is std::this_thread::sleep_for.
  ButtonWatcher(RigIo& io, std::chrono::milliseconds debounce,
                RigClockFunction clock = RigClock::now, SleepFunction sleep = {});

  // Polls the button until a debounced press (true; release and press both seen during this
  // call), until `deadline` or a stop request (false). kBadInput when the rig has no button;
  // the read's error when it fails.
  Result<bool> waitForPress(RigClock::time_point deadline, std::stop_token stop = {});

 private:
  RigIo& io_;
  std::chrono::milliseconds debounce_;
  RigClockFunction clock_;
  SleepFunction sleep_;
};

// Waits for a debounced press of `io`'s button until `deadline`: true when pressed, false at the
// deadline or when a stop is requested (core/interruption.h: Ctrl-C); the button's read errors.
Result<bool> waitForButtonPress(RigIo& io, std::chrono::milliseconds debounce,
                                RigClock::time_point deadline);

}  // namespace glarecam::rig
