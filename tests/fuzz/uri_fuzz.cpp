// libFuzzer target: the device URIs a user types (`--camera`, `--inclinometer`, `[camera] uri`):
// parseCameraUri(), and the simulators' parameter lists (sim:KEY=VALUE,...).
#include <cstddef>
#include <cstdint>

#include "capture/camera_registry.h"
#include "capture/sim/sim_camera.h"
#include "rig/inclinometer/sim_inclinometer.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto text = glarecam::fuzz::asText(data, size);
  if (const auto uri = glarecam::capture::parseCameraUri(text); uri && uri->scheme == "sim")
    (void)glarecam::capture::parseSimCameraId(uri->id, 40.0);
  (void)glarecam::rig::parseSimInclinometerId(text);
  return 0;
}
