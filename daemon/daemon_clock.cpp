#include "daemon/daemon_clock.h"

#include "core/time.h"

namespace glarecam::daemon {

void DaemonClock::waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& wake,
                            SteadyTime deadline, const std::function<bool()>& ready) {
  wake.wait_until(lock, deadline, ready);
}

UtcTime DaemonClock::stackUtcNow(const ClockInstant&) const { return utcNow(); }

UtcTime SystemDaemonClock::utcNow() const { return glarecam::utcNow(); }

SteadyTime SystemDaemonClock::steadyAt(UtcTime utc) const {
  return now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(utc - utcNow());
}

// Not delegating to the constructor below: naming machine_ in a delegating constructor's
// initializer reads a member of an object whose construction has not begun (UBSan: invalid vptr).
TimeLapseClock::TimeLapseClock(UtcTime start, double factor)
    : steady_(machine_), start_utc_(start), start_steady_(machine_.now()), factor_(factor) {}

TimeLapseClock::TimeLapseClock(UtcTime start, double factor, DaemonClock& steady)
    : steady_(steady), start_utc_(start), start_steady_(steady.now()), factor_(factor) {}

UtcTime TimeLapseClock::utcNow() const {
  const std::chrono::duration<double> real = now() - start_steady_;
  return start_utc_ + std::chrono::duration_cast<std::chrono::microseconds>(real * factor_);
}

sun::ClockStatus simulatedClockStatus() {
  return {
      .synchronised = true,
      .detail = "simulated: the simulated sun, α and scene all follow the simulated rig's clock"};
}

sun::ClockStatus TimeLapseClock::clockStatus() const { return simulatedClockStatus(); }

UtcTime TimeLapseClock::stackUtcNow(const ClockInstant& begun) const {
  return begun.utc + std::chrono::duration_cast<std::chrono::microseconds>(now() - begun.steady);
}

void TimeLapseClock::waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& wake,
                               SteadyTime deadline, const std::function<bool()>& ready) {
  steady_.waitUntil(lock, wake, deadline, ready);
}

SteadyTime TimeLapseClock::steadyAt(UtcTime utc) const {
  const std::chrono::duration<double> simulated = utc - start_utc_;
  return start_steady_ +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(simulated / factor_);
}

}  // namespace glarecam::daemon
