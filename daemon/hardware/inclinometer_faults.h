// What glarecamd makes of the inclinometer's faults ([faults] inclinometer, daemon_config.h). The
// rig session measures (rig_session.h: a read that fails, a tilt outside the plausible range);
// this decides what a fault means for capture, and when the sensor is tried again:
//
//   unknown α (default)  the stack is taken, its geometry block saying why α is unknown
//   pause                no stack until the inclinometer reads again
//
// Either way the fault is the status's (DaemonState::inclinometer_fault: the LED's inclinometer
// code, the status line), logged once per distinct message, and the inclinometer is read again
// kInclinometerRetry later, between stacks too, so that the fault clears when it reads. A rig whose
// α is not measured (no [site], no [source]) has no inclinometer faults.
#pragma once

#include <chrono>
#include <optional>

#include "capture/bracketer.h"  // CaptureSettings
#include "daemon/daemon_clock.h"
#include "daemon/daemon_config.h"
#include "daemon/hardware/rig_session.h"
#include "daemon/status/daemon_status.h"
#include "rig/rig_geometry.h"

namespace glarecam::daemon {

// While the inclinometer is faulted, how soon it is read again.
inline constexpr std::chrono::seconds kInclinometerRetry{30};

class InclinometerFaults {
 public:
  explicit InclinometerFaults(const DaemonClock& clock) : clock_(clock) {}

  // Opens the session's sensors; a failure is the status's fault (measure() opens them again).
  void open(RigSession& rig, DaemonState& state);

  struct Measured {
    std::optional<rig::RigGeometry> geometry{};  // none: α unknown (or not measured)
    bool pause = false;                          // no stack now ([faults] inclinometer = "pause")
  };
  // The geometry for a stack at `time` (the sun's; measured now), recorded in `settings`
  // (RigSession::record); on a fault, per `faults`, α unknown or a pause, and the next read
  // kInclinometerRetry from now.
  Measured measure(RigSession& rig, const FaultConfig& faults, DaemonState& state,
                   capture::CaptureSettings& settings, UtcTime time);

  // When the faulted inclinometer is read again (none: no fault).
  std::optional<SteadyTime> retryAt() const { return retry_at_; }
  // Reads it again now: the fault clears when it reads, else the next read is set.
  void retry(RigSession& rig, const FaultConfig& faults, DaemonState& state);

 private:
  const DaemonClock& clock_;
  std::optional<SteadyTime> retry_at_;
};

}  // namespace glarecam::daemon
