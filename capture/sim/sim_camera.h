// The simulated rig as a camera: `sim:` URIs open a Camera that looks at the simulator's glare
// scene (simulated_stack.h) through its 12-bit sensor model, so exposure and gain change the
// frames exactly as the merge's radiometry expects. It stands in for hardware in tests, in the
// demo and for users without a camera. URI parameters, comma-separated after "sim:":
//   module=NAME  seed=N  size=WxH  fov=DEG  alpha=DEG  illuminance=LX
//   surface=NAME|FILE.toml   a physical surface instead of a module's curves (module=NAME is
//                            surface=curves:NAME; SimulationOptions::surface)
//   (e.g. "sim:module=standard,size=640x512", "sim:surface=glare-reduced")
//   target=dark|flat|linearity|noise|luminance|board   a calibration target instead of the module
// The scene's α comes from the camera's SceneSource (camera_registry.h: the rig's measured α,
// or the capture's --alpha), asked before each bracket; the scene is rendered again when it
// changed. Without one, the URI's alpha=, else the simulator's default. A URI's alpha= fixes the
// scene: an α from the source that contradicts it is refused (at open, or by the bracket), so a
// stack never records one α and shows another. An α up to
// kSceneAlphaSlackDeg past the method's 80° (an inclinometer's noise around an 80° target) shows
// the 80° scene; beyond that a bracket is refused. The sun that lights the scene is the source's
// too (a rig's clear-sky sun), unless the URI's illuminance= fixes it; else 100 klx.
// Its frames' timestamps are a camera's clock, as if behind Gigabit Ethernet: from 0 at open, each
// frame stamped at the start of its exposure, the clock advancing by the exposure and the frame's
// transfer (bracketFloorS, camera.h), so a bracket reports the time a camera would take, while
// the simulator itself takes only its rendering time.
// The camera knows its calibration (CameraInfo::calibration) and the truth of what it shows
// (SceneTruthSource), which the bracketer writes beside its stacks as truth.json.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "capture/camera.h"
#include "capture/camera_registry.h"
#include "capture/sim/simulated_stack.h"
#include "core/error.h"

namespace glarecam::capture {

// How far past the limit curve's 80° a source's α may go and still show the 80° scene: the
// simulated inclinometer's noise (0.004°) carries a stack aimed at 80° just past it.
inline constexpr double kSceneAlphaSlackDeg = 0.05;

// A camera that knows the truth of the scene it shows (truth.json, docs/simulate.md), so that the
// pipeline can be checked against it. Only simulated cameras do.
class SceneTruthSource {
 public:
  virtual ~SceneTruthSource() = default;
  virtual std::optional<nlohmann::json> sceneTruth() const = 0;
};

// The truth `camera` knows, when it is a SceneTruthSource; nullopt for real cameras.
std::optional<nlohmann::json> sceneTruthOf(const Camera& camera);

// The simulation a `sim:` URI's parameters describe; `scene_alpha_deg`: the α the rig asks for,
// which an alpha= in the URI must not contradict.
Result<SimulationOptions> parseSimCameraId(std::string_view id,
                                           std::optional<double> scene_alpha_deg = std::nullopt);

std::unique_ptr<CameraBackend> makeSimCameraBackend(SceneSource scene_source = {});

}  // namespace glarecam::capture
