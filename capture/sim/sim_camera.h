// The simulated rig as a camera: `sim:` URIs open a Camera that looks at the simulator's glare
// scene (simulated_stack.h) through its 12-bit sensor model, so exposure and gain change the
// frames exactly as the merge's radiometry expects. It stands in for hardware in tests, in the
// demo and for users without a camera. URI parameters, comma-separated after "sim:":
//   module=NAME  seed=N  size=WxH  fov=DEG  alpha=DEG   (e.g. "sim:module=standard,size=640x512")
//   target=dark|flat|linearity|noise|luminance|board   a calibration target instead of the module
// α defaults to CameraOptions::simulated_alpha_deg, then to the simulator's default.
#pragma once

#include <memory>
#include <string_view>

#include "capture/camera.h"
#include "capture/sim/simulated_stack.h"
#include "core/error.h"

namespace glarecam::capture {

// The simulation a `sim:` URI's parameters describe.
Result<SimulationOptions> parseSimCameraId(std::string_view id, const CameraOptions& options);

std::unique_ptr<CameraBackend> makeSimCameraBackend();

}  // namespace glarecam::capture
