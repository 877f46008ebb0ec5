// `glarecam simulate`: a complete recorded stack of a simulated rig with known ground truth.
// The scene is the module's glare lobe at alpha (module_model.h) over a background, seen by a
// pinhole camera (optionally distorted) through a 12-bit sensor (sensor_model.h), bracketed
// like a real auto-bracket (bracketing.h). The same pieces back the `sim:` camera.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "capture/bracketing.h"
#include "capture/sim/glare_scene.h"
#include "capture/sim/sensor_model.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

// The prefix of a `surface` drawn from a module's empirical curves instead of a surface model.
inline constexpr std::string_view kCurvesPrefix = "curves:";

// The camera (SimulatedCameraModel: size, seed, sensor, lens, K) and the scene in front of it.
struct SimulationOptions : SimulatedCameraModel {
  double alpha_deg = 40.0;
  // What the camera looks at: "curves:NAME", the lobe drawn from a registered module's empirical
  // curves (module_model.h; the default, the paper's standard module), or a physical surface by
  // name or TOML file (surface/surface_catalogue.h: standard, glare-reduced, gaussian, FILE.toml)
  // rendered under the sun's disc (surface_scene.h).
  std::string surface = std::string(kCurvesPrefix) + "standard";
  std::array<double, 2> lobe_offset_deg{0, 0};  // lobe centre from the optical axis [h, v]
  double lobe_orientation_deg = 0.0;
  double background_cd_m2 = 3000.0;  // sky reflected in the module glass, an overcast-sky order
  double peak_scale = 1.0;  // multiplies the module's luminance maximum (e.g. below-limit scenes)
  double nd_transmission = 1.0e-3;  // ND 3.0 filter: sun reflections need it
  // The sun that lights the scene: its direct normal illuminance E scales every luminance of the
  // scene by E / E_ref (the module model's values are the module's at the reference,
  // docs/method.md "Reference illuminance"), and is recorded as the manifest's `source` (origin
  // given, its uncertainty as stated) unless `record_source` is off, which makes an unreferred
  // stack. truth.json gives the truth at the reference and as lit.
  double source_illuminance_lx = kDefaultReferenceIlluminanceLx;
  double source_illuminance_u_lx = 0;
  bool record_source = true;
  BracketOptions bracket;
  SensorDefects defects;       // none by default: a clean sensor (the sensor's seed places them)
  bool show_progress = false;  // progress on stderr (the CLI turns it on)
  // The `sim:` camera only: a calibration target (calibration_targets.h) instead of the module.
  std::string calibration_target;
  Status validate() const;
  // The module's name in stack ids and manifests: the curves' module ("standard"), or the
  // surface's name or file stem after "surface-" ("surface-glare-reduced").
  std::string moduleLabel() const;
};

struct SimulatedStack {
  StackManifest manifest;
  std::vector<RawFrame> frames;
  FloatImage true_luminance_cd_m2;  // as lit
  SceneTruth truth;                 // at the reference illuminance
  SceneTruth truth_as_lit;          // under the scene's own source (= truth at E = E_ref)
  double source_illuminance_lx = kDefaultReferenceIlluminanceLx;
  std::array<double, 2> centre_pixel{0, 0};
  BracketPlan bracket;
  SensorDefectMap defects;  // empty images when the sensor has none
  nlohmann::json truthJson() const;
};

// The simulated camera's model: square pixels, principal point at the centre, focal length from
// the horizontal field of view.
Intrinsics pinholeIntrinsics(int width, int height, double horizontal_fov_deg,
                             const std::array<double, 5>& distortion = {});

// The scene the simulated rig looks at, before any sensor: what the `sim:` camera and the fake
// GigE Vision camera expose frames of.
struct SimulatedScene {
  FloatImage true_luminance_cd_m2;  // as lit by the options' source
  SceneTruth truth;                 // at the reference illuminance
  SceneTruth truth_as_lit;
  double source_illuminance_lx = kDefaultReferenceIlluminanceLx;
  Calibration calibration;  // the simulated camera's, exact by construction
  std::array<double, 2> centre_pixel{0, 0};
};

Result<SimulatedScene> renderSimulatedScene(const SimulationOptions& options);

// truth.json (schema glarecam.truth/1) of a scene: maximum, limit, both axes, glare, centre, at
// the reference illuminance; under "as_lit" the same under the scene's own source.
nlohmann::json sceneTruthJson(const SimulatedScene& scene, double alpha_deg);

// The calibration block of the simulated camera (its sensor, K, f-number and pinhole model).
Calibration simulatedCalibration(const SimulationOptions& options);

// The noise seed of the `frame`-th frame a simulated camera takes with `seed`: every frame of
// every seed gets its own noise (seeds are spaced further apart than a session takes frames).
std::uint64_t simulatedFrameSeed(std::uint64_t seed, std::uint64_t frame);

// A frame of the simulated camera at an exposure and gain, with its f-number and ND filter.
FrameSpec simulatedFrameSpec(const SimulationOptions& options, double exposure_us, double gain_db);

Result<SimulatedStack> simulateStack(const SimulationOptions& options);

// Writes the stack atomically with truth.json inside it, beside stack.json.
Status writeSimulatedStack(const std::filesystem::path& directory, const SimulatedStack& stack);

}  // namespace glarecam::capture
