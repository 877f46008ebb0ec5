#include "daemon/hardware/inclinometer_faults.h"

#include <spdlog/spdlog.h>

namespace glarecam::daemon {

void InclinometerFaults::open(RigSession& rig, DaemonState& state) {
  const Status opened = rig.openSensors();
  if (opened) {
    state.inclinometer_fault.clear();
    return;
  }
  if (opened.error().message != state.inclinometer_fault)
    spdlog::error("glarecamd: {}", opened.error().message);
  state.inclinometer_fault = opened.error().message;
}

InclinometerFaults::Measured InclinometerFaults::measure(RigSession& rig, const FaultConfig& faults,
                                                         DaemonState& state,
                                                         capture::CaptureSettings& settings,
                                                         UtcTime time) {
  if (!rig.measuresAlpha()) return {};
  const Result<rig::RigGeometry> measured = rig.measure(time, clock_.clockStatus());
  state.inclinometer_pauses = faults.inclinometer == InclinometerFaultPolicy::kPause;
  RigSession::record(measured, settings);
  if (measured) {
    if (!state.inclinometer_fault.empty()) spdlog::info("glarecamd: the inclinometer reads again");
    state.inclinometer_fault.clear();
    retry_at_.reset();
    return {.geometry = *measured};
  }
  const bool pause = state.inclinometer_pauses;
  if (measured.error().message != state.inclinometer_fault)
    spdlog::error("glarecamd: {}; {}", measured.error().message,
                  pause ? "capture pauses" : "the stack's α is unknown");
  state.inclinometer_fault = measured.error().message;
  retry_at_ = clock_.now() + kInclinometerRetry;
  return {.pause = pause};
}

void InclinometerFaults::retry(RigSession& rig, const FaultConfig& faults, DaemonState& state) {
  retry_at_.reset();
  capture::CaptureSettings unused;
  measure(rig, faults, state, unused, clock_.utcNow());
}

}  // namespace glarecam::daemon
