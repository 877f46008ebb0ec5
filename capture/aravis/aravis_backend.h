// GenICam cameras through Aravis 0.8: GigE Vision and USB3 Vision cameras, Aravis's fake
// cameras (in-process "Fake" interface, and the GigE Vision fake camera of fake_gv_camera.h).
// URIs: "aravis:" (the first camera found) or "aravis:<device id, serial, user id or IP>".
// The camera is set to the deepest mono pixel format (Mono16, Mono12, else Mono8 with a warning),
// software trigger when the camera has one (free-running otherwise, dropping the frames exposed
// before a change), and every frame's exposure and gain are read back from the camera.
// Incomplete buffers are retried, never stored; a camera that fires control-lost fails the
// capture with a clear error.
#pragma once

#include <memory>

#include "capture/camera.h"

namespace glarecam::capture {

std::unique_ptr<CameraBackend> makeAravisBackend();

// Makes Aravis's in-process fake camera ("Fake_1", a diagonal ramp scaled by exposure and gain)
// visible to `aravis:` URIs: for tests and for trying the backend without a camera.
void enableAravisFakeInterface();

}  // namespace glarecam::capture
