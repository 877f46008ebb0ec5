#include "capture/rig_stack.h"

namespace glarecam::capture {

Status recordBracketGeometry(const RigSensors& sensors, const RigGeometry& measured,
                             CapturedStack& stack, UtcTime start, UtcTime end) {
  if (!measured.sun) {
    recordAlpha(stack, measured.alpha_deg, geometryJson(measured));
    return {};
  }
  RigGeometry retimed;
  GLARECAM_ASSIGN(retimed, sensors.retime(measured, start + (end - start) / 2));
  recordAlpha(stack, retimed.alpha_deg, geometryJson(retimed));
  return {};
}

}  // namespace glarecam::capture
