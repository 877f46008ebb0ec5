// The daemon's time, injectable. Two timelines: the steady clock for timers (the watchdog, the
// interval schedule, backoff) and the wall clock (UTC) for the sun, α and the stacks' timestamps,
// with the wall clock's synchronisation state (a wrong clock is a wrong α).
//
// SystemDaemonClock is the machine's. TimeLapseClock (glarecamd --simulate) runs the wall clock
// faster than real time from a chosen start, so that a simulated sun sweeps α in minutes; but not
// during a stack (StackTimeline): from the instant its α is measured to the end of its bracket the
// wall clock runs at real rate, so that the sun moves as little in a simulated bracket as in a real
// one (0.01°), and the α recorded for the bracket's middle is the α the scene was drawn at.
// Tests use a manual clock (tests/daemon/daemon_test_support.h) that jumps to each deadline
// instead of waiting: hours of schedule in milliseconds, and no sleeping.
//
// waitUntil() is how the event loop sleeps: until `deadline` or until `ready()` holds, with
// `lock` held on `wake`'s mutex around every check, like condition_variable::wait_until.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

#include "core/time.h"
#include "sun/clock_sync.h"

namespace glarecam::daemon {

using SteadyTime = std::chrono::steady_clock::time_point;

// An instant on both of the daemon's time lines.
struct ClockInstant {
  UtcTime utc;
  SteadyTime steady;
};

class DaemonClock {
 public:
  virtual ~DaemonClock() = default;
  virtual SteadyTime now() const = 0;
  virtual UtcTime utcNow() const = 0;
  // The wall clock's state now (synchronised, its error).
  virtual sun::ClockStatus clockStatus() const = 0;
  // The steady time at which the wall clock will read `utc` (for timers set to a wall time).
  virtual SteadyTime steadyAt(UtcTime utc) const = 0;
  // The wall time now on the time line of a stack begun at `begun` (StackTimeline): by default
  // the wall clock's.
  virtual UtcTime stackUtcNow(const ClockInstant& begun) const;
  // Whether the wall clock is a simulated one (a time lapse): its times are not the machine's.
  virtual bool simulated() const { return false; }
  // Waits until `deadline` or until `ready()` (checked first, and after every wake-up). By
  // default in real time on the steady clock.
  virtual void waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& wake,
                         SteadyTime deadline, const std::function<bool()>& ready);
};

class SystemDaemonClock final : public DaemonClock {
 public:
  SteadyTime now() const override { return std::chrono::steady_clock::now(); }
  UtcTime utcNow() const override;
  sun::ClockStatus clockStatus() const override { return sun::systemClockStatus(); }
  SteadyTime steadyAt(UtcTime utc) const override;
};

// The state of a simulated clock (a time lapse, the simulated rig's: simulated_rig.h): synchronised
// by construction, for the simulated sun, the α measured and the scene drawn all follow it.
sun::ClockStatus simulatedClockStatus();

// Wall time = `start` + `factor` × (steady time since construction), on the steady time (and
// the waits) of the machine, or of another clock (`steady`: tests run it on a manual clock);
// always synchronised. A stack's time line runs at real rate from its start.
class TimeLapseClock final : public DaemonClock {
 public:
  TimeLapseClock(UtcTime start, double factor);
  TimeLapseClock(UtcTime start, double factor, DaemonClock& steady);
  SteadyTime now() const override { return steady_.now(); }
  UtcTime utcNow() const override;
  sun::ClockStatus clockStatus() const override;
  SteadyTime steadyAt(UtcTime utc) const override;
  UtcTime stackUtcNow(const ClockInstant& begun) const override;
  bool simulated() const override { return true; }
  void waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& wake,
                 SteadyTime deadline, const std::function<bool()>& ready) override;

 private:
  SystemDaemonClock machine_;
  DaemonClock& steady_;
  UtcTime start_utc_;
  SteadyTime start_steady_;
  double factor_;
};

// One stack's time line, from the instant its α is measured (begun(): the scene a simulated
// camera draws is at that α) to the end of its bracket: the wall clock, except on a time lapse,
// where it runs at real rate from begun() (DaemonClock::stackUtcNow).
class StackTimeline {
 public:
  explicit StackTimeline(const DaemonClock& clock)
      : clock_(clock), begun_{.utc = clock.utcNow(), .steady = clock.now()} {}
  UtcTime begun() const { return begun_.utc; }
  UtcTime now() const { return clock_.stackUtcNow(begun_); }

 private:
  const DaemonClock& clock_;
  ClockInstant begun_;
};

}  // namespace glarecam::daemon
