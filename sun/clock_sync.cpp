#include "sun/clock_sync.h"

#include <spdlog/spdlog.h>
#include <sys/timex.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/time.h"

namespace glarecam::sun {

namespace {

constexpr double kSecondsPerMicrosecond = 1e-6;

}  // namespace

ClockStatus interpretClockState(int state, int status_flags, long max_error_us, long est_error_us) {
  ClockStatus clock;
  clock.max_error_s = double(max_error_us) * kSecondsPerMicrosecond;
  clock.estimated_error_s = double(est_error_us) * kSecondsPerMicrosecond;
  if (state == TIME_ERROR || (status_flags & STA_UNSYNC)) {
    clock.detail =
        "the kernel reports it unsynchronised (no NTP/PTP/GNSS time source: check "
        "`timedatectl` or `chronyc tracking`)";
    return clock;
  }
  clock.synchronised = true;
  return clock;
}

ClockStatus systemClockStatus() {
  timex tx{};  // modes 0: read only
  const int state = adjtimex(&tx);
  if (state < 0) {  // the state is unknown: as good as unsynchronised
    ClockStatus clock;
    clock.detail =
        std::string("its state is unknown (adjtimex failed: ") + std::strerror(errno) + ")";
    return clock;
  }
  return interpretClockState(state, tx.status, tx.maxerror, tx.esterror);
}

Result<UtcTime> givenTimeOrNow(const std::optional<std::string>& text) {
  if (text) return parseIsoTime(*text);
  const ClockStatus clock = systemClockStatus();
  if (!clock.synchronised)
    spdlog::warn("the system clock is not synchronised: {}; a wrong clock is a wrong sun position",
                 clock.detail);
  return utcNow();
}

}  // namespace glarecam::sun
