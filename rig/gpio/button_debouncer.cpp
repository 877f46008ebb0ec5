#include "rig/gpio/button_debouncer.h"

#include <algorithm>
#include <thread>
#include <utility>

#include "core/interruption.h"

namespace glarecam::rig {

ButtonDebouncer::ButtonDebouncer(std::chrono::nanoseconds debounce) : debounce_(debounce) {}

bool ButtonDebouncer::update(bool pressed, RigClock::time_point at) {
  const Level level = pressed ? Level::kPressed : Level::kReleased;
  if (raw_ != level) {
    raw_ = level;
    raw_since_ = at;
  }
  if (stable_ == level || at - raw_since_ < debounce_) return false;
  const Level before = stable_;
  stable_ = level;
  return level == Level::kPressed && before == Level::kReleased;
}

ButtonWatcher::ButtonWatcher(RigIo& io, std::chrono::milliseconds debounce, RigClockFunction clock,
                             SleepFunction sleep)
    : io_(io), debounce_(debounce), clock_(std::move(clock)), sleep_(std::move(sleep)) {
  if (!sleep_) sleep_ = [](RigClock::duration duration) { std::this_thread::sleep_for(duration); };
}

Result<bool> ButtonWatcher::waitForPress(RigClock::time_point deadline, std::stop_token stop) {
  if (!io_.hasButton()) return badInput("no GPIO button line is configured: cannot wait for it");
  ButtonDebouncer debouncer(debounce_);
  while (!stop.stop_requested()) {
    bool pressed = false;
    GLARECAM_ASSIGN(pressed, io_.buttonPressed());
    const RigClock::time_point now = clock_();
    if (debouncer.update(pressed, now)) return true;
    if (now >= deadline) return false;
    sleep_(std::min<RigClock::duration>(kButtonPollPeriod, deadline - now));
  }
  return false;
}

Result<bool> waitForButtonPress(RigIo& io, std::chrono::milliseconds debounce,
                                RigClock::time_point deadline) {
  // One wait (a press may straddle any slicing), stopped from a thread that watches for signals.
  ButtonWatcher watcher(io, debounce);
  return untilStopRequested(
      [&](std::stop_token stop) { return watcher.waitForPress(deadline, stop); });
}

}  // namespace glarecam::rig
