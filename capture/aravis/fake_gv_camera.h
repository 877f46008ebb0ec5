// A GigE Vision camera that shows our scene: Aravis's GigE Vision fake camera (ArvGvFakeCamera)
// served on a network interface (loopback by default), whose frames are the simulator's glare
// scene (simulated_stack.h) exposed at the exposure and gain the client set. The real Aravis
// backend can then be tested end to end over real GigE Vision on any machine, packet loss
// included, and users without a camera can try `glarecam capture` against it.
// Like a camera, and unlike Aravis's own fake, it takes each frame's exposure time between the
// trigger and sending the frame (rendering counts towards it), so a bracket lasts at least the sum
// of its exposures. Aravis's fake camera answers control packets on the thread that sends frames,
// so none are answered during an exposure, and the client gives up on the control channel after a
// few seconds: an exposure longer than 2 s is sent after 2 s.
// Pixel formats: Mono16 carries the simulated 12-bit sensor's values shifted up by 4 bits (as
// cameras MSB-align Mono12 in Mono16), Mono8 its top 8 bits; the GainRaw register is read as dB.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "capture/sim/simulated_stack.h"
#include "core/error.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

// The fake camera's default scene: 640x512 frames (a VGA-class GigE sensor) with a 20° field of
// view, so that the glare lobe spans about a hundred pixels (16 px per degree).
SimulationOptions fakeCameraScene();

struct FakeGvCameraOptions {
  std::string interface_address = "127.0.0.1";  // an interface name or IPv4 address
  std::string serial = "GV01";
  SimulationOptions scene = fakeCameraScene();
  double packet_loss = 0.0;  // fraction of GVSP packets dropped, [0, 1)
  // How often the fake camera looks for a software trigger: sets its trigger latency.
  double trigger_poll_hz = 1000.0;
  // Send the first rendering of each exposure again instead of new noise: benchmarks then
  // measure the transport and the backend, not the simulator.
  bool reuse_frames = false;
  Status validate() const;
};

class FakeGvCamera {
 public:
  // Renders the scene and starts serving; fails when the interface cannot be bound (another
  // GigE Vision device already answers on it).
  static Result<std::unique_ptr<FakeGvCamera>> start(const FakeGvCameraOptions& options);
  ~FakeGvCamera();
  FakeGvCamera(const FakeGvCamera&) = delete;
  FakeGvCamera& operator=(const FakeGvCamera&) = delete;

  std::string uri() const;  // what `glarecam capture --camera` takes
  const SimulatedScene& scene() const;
  // The calibration of its frames in `pixel_format` (Mono16 or Mono8), the simulated ND filter
  // included in K (a client records no ND filter).
  Result<Calibration> calibration(std::string_view pixel_format) const;

 private:
  struct State;
  explicit FakeGvCamera(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The calibrations of both pixel formats (fake-camera-mono16.json, fake-camera-mono8.json) and
// the scene's truth at `alpha_deg` (fake-camera-truth.json) in `directory` (created), each
// written atomically: what a capture from the camera is checked against.
Status writeFakeCameraFiles(const FakeGvCamera& camera, const std::filesystem::path& directory,
                            double alpha_deg);

}  // namespace glarecam::capture
