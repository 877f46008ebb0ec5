#include "daemon/rig_stack.h"

namespace glarecam::daemon {

Status recordBracketGeometry(const rig::RigSensors& sensors, const rig::RigGeometry& measured,
                             capture::CapturedStack& stack, UtcTime start, UtcTime end) {
  if (!measured.sun) {
    capture::recordAlpha(stack, measured.alpha_deg, rig::geometryJson(measured));
    return {};
  }
  rig::RigGeometry retimed;
  GLARECAM_ASSIGN(retimed, sensors.retime(measured, start + (end - start) / 2));
  capture::recordAlpha(stack, retimed.alpha_deg, rig::geometryJson(retimed));
  return {};
}

}  // namespace glarecam::daemon
