// Is the system clock synchronised? A wrong clock is a wrong sun position, hence a wrong α (the
// sun moves up to 0.25° a minute), so the rig checks the kernel's NTP state (adjtimex(2), as
// chrony, systemd-timesyncd and ntpd leave it) before trusting the time, and widens α's
// uncertainty by the kernel's error estimate.
#pragma once

#include <optional>
#include <string>

#include "core/error.h"
#include "core/time.h"

namespace glarecam::sun {

struct ClockStatus {
  bool synchronised = false;
  double max_error_s = 0.0;        // the kernel's bound while synchronised (timex.maxerror)
  double estimated_error_s = 0.0;  // its estimate (timex.esterror)
  std::string detail;              // for a warning: why it is not synchronised

  // The clock's standard uncertainty for α: the kernel's estimate while synchronised. Unknown
  // otherwise: the kernel stops growing maxerror at 16 s, a cap and not a bound, and a clock
  // that was never synchronised (a board without a battery-backed clock) can be hours off.
  std::optional<double> uncertaintyS() const {
    if (!synchronised) return std::nullopt;
    return estimated_error_s;
  }
};

// What adjtimex(2) returned: `state` (TIME_OK, TIME_ERROR, ...), timex.status flags and the two
// errors in microseconds. Pure, so that every state is testable.
ClockStatus interpretClockState(int state, int status_flags, long max_error_us, long est_error_us);

// The system clock now (a read-only adjtimex call; needs no privilege).
ClockStatus systemClockStatus();

// The instant `text` gives (ISO 8601, core/time.h), else the system clock's now, with a warning
// when the clock is not synchronised (a wrong clock is a wrong sun position).
Result<UtcTime> givenTimeOrNow(const std::optional<std::string>& text);

}  // namespace glarecam::sun
