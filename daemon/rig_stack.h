// What the rig's sensors add to a captured stack: α and the geometry block for the bracket's
// middle. The inclinometer is read before the bracket; the sun moves while the frames expose, so
// the reading is retimed to the middle of the bracket (a fixed lab source does not move).
#pragma once

#include "capture/bracketer.h"
#include "core/error.h"
#include "rig/rig_geometry.h"

namespace glarecam::daemon {

// Records α and the geometry of `measured` retimed to the middle of [start, end] in the stack's
// manifest (and its id). On failure the stack is left as it was and the error returned.
Status recordBracketGeometry(const rig::RigSensors& sensors, const rig::RigGeometry& measured,
                             capture::CapturedStack& stack, UtcTime start, UtcTime end);

}  // namespace glarecam::daemon
