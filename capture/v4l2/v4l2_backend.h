// The V4L2 camera backend: "v4l2:/dev/videoN", a video capture node with a mono pixel format
// (GREY, Y10, Y12, Y16; the deepest by default) and V4L2_CID_EXPOSURE_ABSOLUTE (UVC and many
// bridge drivers). It is built on every Linux: it needs only the kernel headers, used in
// capture/v4l2/*.cpp alone. capture() streams through mmap'd buffers, writes each request's
// controls in one VIDIOC_S_EXT_CTRLS, reads them back for the applied values, and drops frames
// until the write took effect (v4l2_controls.h). CapturedFrame::retries counts every frame
// discarded for a request: stale ones and flagged or short ones (only the latter are bounded by
// CameraOptions::max_frame_retries). Tests inject a simulated V4l2Device through the opener.
#pragma once

#include <memory>
#include <string>

#include "capture/camera.h"
#include "capture/v4l2/v4l2_controls.h"
#include "capture/v4l2/v4l2_device.h"

namespace glarecam::capture {

struct V4l2Options {
  int settle_frames = kDefaultSettleFrames;  // frames dropped after a control write
  int buffer_count = 4;                      // mmap'd buffers asked of the driver
  std::string device_directory = "/dev";     // where list() looks for video* nodes
};

std::unique_ptr<CameraBackend> makeV4l2Backend();
std::unique_ptr<CameraBackend> makeV4l2Backend(V4l2DeviceOpener opener, V4l2Options options = {});

}  // namespace glarecam::capture
