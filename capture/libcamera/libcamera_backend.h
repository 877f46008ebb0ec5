// The libcamera backend: `libcamera:<id>` cameras (CSI-2 sensors on the Raspberry Pi and other
// boards whose pipelines libcamera drives), captured as raw frames with manual exposure and gain.
// Each completed request is matched to its bracket step by the exposure in its metadata, since
// a sensor applies controls a few frames late. Only tested libcamera versions are accepted; with
// no camera present list() is empty and open() fails with a hardware error naming the URI.
// libcamera's headers stay in libcamera_backend.cpp; the pure logic is in request_matching.h.
#pragma once

#include <memory>

#include "capture/camera.h"

namespace glarecam::capture {

std::unique_ptr<CameraBackend> makeLibcameraBackend();

}  // namespace glarecam::capture
