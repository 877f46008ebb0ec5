// Aravis's GigE Vision fake camera (capture/aravis/fake_gv_camera.h) serving a glare scene on
// loopback, for the tests of the Aravis backend and of the fake camera itself.
#pragma once

#include "capture/aravis/fake_gv_camera.h"

namespace glarecam::testing {

// The scene at `alpha_deg`, GVSP packets dropped at the rate `packet_loss`.
inline capture::FakeGvCameraOptions loopbackScene(double alpha_deg, double packet_loss = 0) {
  capture::FakeGvCameraOptions options;
  // 16 px per degree, as the issue-2 whole-chain test: axes 35..130 px.
  options.scene.width = 320;
  options.scene.height = 256;
  options.scene.horizontal_fov_deg = 20;
  options.scene.alpha_deg = alpha_deg;
  options.scene.seed = 11;
  options.packet_loss = packet_loss;
  return options;
}

}  // namespace glarecam::testing
