// Is the system clock synchronised? A wrong clock is a wrong sun position, hence a wrong α (the
// sun moves up to 0.25° a minute), so the rig checks the kernel's NTP state (adjtimex(2), as
// chrony, systemd-timesyncd and ntpd leave it) before trusting the time, and widens α's
// uncertainty by the kernel's error estimate.
#pragma once

#include <string>

namespace glarecam::capture {

struct ClockStatus {
  bool synchronised = false;
  double max_error_s = 0.0;        // the kernel's bound on the clock error (timex.maxerror)
  double estimated_error_s = 0.0;  // its estimate (timex.esterror)
  std::string detail;              // for a warning: why it is not synchronised

  // The clock's standard uncertainty for α: the estimate when synchronised, else the bound.
  double uncertaintyS() const { return synchronised ? estimated_error_s : max_error_s; }
};

// What adjtimex(2) returned: `state` (TIME_OK, TIME_ERROR, ...), timex.status flags and the two
// errors in microseconds. Pure, so that every state is testable.
ClockStatus interpretClockState(int state, int status_flags, long max_error_us, long est_error_us);

// The system clock now (a read-only adjtimex call; needs no privilege).
ClockStatus systemClockStatus();

}  // namespace glarecam::capture
