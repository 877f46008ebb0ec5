#include "capture/sim/sim_camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "capture/bracketing.h"
#include "capture/sim/calibration_targets.h"
#include "capture/sim/module_model.h"
#include "capture/sim/sensor_model.h"
#include "core/uri_parameters.h"
#include "pipeline/limit_curve.h"

namespace glarecam::capture {
namespace {

// The simulated camera's controls: a machine-vision sensor's usual range (the same bounds the
// simulator's bracket uses), 1 µs exposure resolution and 0–24 dB analogue gain.
constexpr double kSimMinGainDb = 0.0;
constexpr double kSimMaxGainDb = 24.0;
constexpr std::string_view kSimSerial = "SIM-0001";
constexpr std::string_view kSimPixelFormat = "Mono12";  // SensorModel's 12-bit ADC
constexpr double kMaxSizeParameter = 1 << 20;           // converts to int exactly
constexpr double kMaxSeedParameter = 0x1p53;            // whole numbers a double holds exactly

constexpr std::string_view kUriName = "camera URI sim:";

Result<double> parseNumber(std::string_view text, std::string_view uri_key) {
  return parseUriNumber(text, uri_key, kUriName);
}

Status applyParameter(std::string_view key, std::string_view value, SimulationOptions& sim) {
  if (key == "module") {
    sim.surface = std::string(kCurvesPrefix) + std::string(value);
    return {};
  }
  if (key == "surface") {
    sim.surface = std::string(value);
    return {};
  }
  if (key == "target") {
    const auto target = parseCalibrationTarget(value);
    if (!target) return std::unexpected(target.error());
    sim.calibration_target = std::string(value);
    return {};
  }
  if (key == "size") {
    const auto x = value.find('x');
    double width = 0, height = 0;
    const auto bad_size = [&] {
      return badInput(fmt::format("camera URI sim: size={} must be WIDTHxHEIGHT", value));
    };
    if (x == std::string_view::npos) return bad_size();
    auto parsed_width = parseNumber(value.substr(0, x), "size");
    auto parsed_height = parseNumber(value.substr(x + 1), "size");
    if (!parsed_width || !parsed_height) return bad_size();
    width = *parsed_width;
    height = *parsed_height;
    // Out of range here would be undefined in the conversion; validate() names the real limits.
    if (!(width >= 1 && height >= 1 && width <= kMaxSizeParameter && height <= kMaxSizeParameter)) {
      return badInput(fmt::format("camera URI sim: size={} is out of range", value));
    }
    sim.width = static_cast<int>(width);
    sim.height = static_cast<int>(height);
    return {};
  }
  double number = 0;
  GLARECAM_ASSIGN(number, parseNumber(value, key));
  if (key == "seed") {
    if (!(number >= 0 && number < kMaxSeedParameter && number == std::floor(number))) {
      return badInput(fmt::format("camera URI sim: seed={} must be a whole number >= 0", value));
    }
    sim.seed = static_cast<std::uint64_t>(number);
  } else if (key == "fov") {
    sim.horizontal_fov_deg = number;
  } else if (key == "alpha") {
    sim.alpha_deg = number;
  } else if (key == "illuminance") {
    sim.source_illuminance_lx = number;  // validate() names the range
  } else {
    return badInput(fmt::format(
        "camera URI sim: unknown parameter '{}' (known: module, surface, seed, size, fov, "
        "alpha, illuminance, target)",
        key));
  }
  return {};
}

// The α a source's value shows: the method's range, with the slack past 80°.
Result<double> shownAlphaDeg(double alpha_deg) {
  if (alpha_deg > pipeline::kMaxLimitAlphaDeg &&
      alpha_deg <= pipeline::kMaxLimitAlphaDeg + kSceneAlphaSlackDeg)
    return pipeline::kMaxLimitAlphaDeg;
  if (!(alpha_deg >= 0 && alpha_deg <= pipeline::kMaxLimitAlphaDeg)) {
    return badInput(
        fmt::format("camera URI sim: the simulated scene's α must be within 0…{:g}° "
                    "(the method's range), not {:g}",
                    pipeline::kMaxLimitAlphaDeg, alpha_deg));
  }
  return alpha_deg;
}

// A URI's alpha= fixes the scene: every α the rig asks for must show that one.
Status agreesWithUriAlpha(double uri_alpha_deg, double asked_deg) {
  const Result<double> shown = shownAlphaDeg(asked_deg);
  if (shown && *shown == uri_alpha_deg) return {};
  return badInput(
      fmt::format("camera URI sim: alpha={:g} contradicts the capture's α {:g} (--alpha, or "
                  "measured through --config); give the scene's α once",
                  uri_alpha_deg, asked_deg));
}

std::string sceneDetail(const SimulationOptions& options) {
  return fmt::format("α {:g}°, {}x{}, seed {}", options.alpha_deg, options.width, options.height,
                     options.seed);
}

class SimCamera final : public Camera, public SceneTruthSource {
 public:
  // `alpha_fixed`: the URI gave alpha=, which every α the source gives must agree with;
  // `illuminance_fixed`: the URI gave illuminance=, which the source's does not change.
  SimCamera(SimulationOptions options, SimulatedScene scene, std::string uri,
            SceneSource scene_source, bool alpha_fixed, bool illuminance_fixed)
      : options_(std::move(options)),
        scene_(std::move(scene)),
        scene_source_(std::move(scene_source)),
        alpha_fixed_(alpha_fixed),
        illuminance_fixed_(illuminance_fixed) {
    info_ = {.uri = std::move(uri),
             .backend = "sim",
             .vendor = "glarecam",
             .model = "simulated rig (" + options_.moduleLabel() + " module)",
             .serial = std::string(kSimSerial),
             .detail = sceneDetail(options_),
             .optics = {.f_number = options_.f_number, .nd_transmission = options_.nd_transmission},
             .calibration = scene_.calibration};
  }

  const CameraInfo& info() const override { return info_; }

  CameraLimits limits() const override {
    return {.min_exposure_us = options_.bracket.min_exposure_us,
            .max_exposure_us = options_.bracket.max_exposure_us,
            .exposure_step_us = options_.bracket.exposure_step_us,
            .min_gain_db = kSimMinGainDb,
            .max_gain_db = kSimMaxGainDb};
  }

  SensorFormat format() const override {
    return {.pixel_format = std::string(kSimPixelFormat),
            .width = options_.width,
            .height = options_.height,
            .bits_per_pixel = 16};
  }

  std::optional<nlohmann::json> sceneTruth() const override {
    if (!options_.calibration_target.empty())
      return nlohmann::json{{"schema", kTruthSchema}, {"target", options_.calibration_target}};
    return sceneTruthJson(scene_, options_.alpha_deg);
  }

 private:
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override {
    GLARECAM_CHECK(showSourceScene());
    std::vector<CapturedFrame> frames;
    frames.reserve(requests.size());
    for (const ExposureRequest& request : requests) {
      CapturedFrame frame;
      frame.exposure_us = applied(request.exposure_us);
      frame.gain_db = std::clamp(request.gain_db, kSimMinGainDb, kSimMaxGainDb);
      const FrameSpec spec = simulatedFrameSpec(options_, frame.exposure_us, frame.gain_db);
      frame.image = exposeFrame(scene_.true_luminance_cd_m2, spec, scene_.calibration,
                                options_.sensor, simulatedFrameSeed(options_.seed, frames_taken_));
      frame.timestamp_ns = camera_clock_ns_;
      const ExposureRequest applied_request{frame.exposure_us, frame.gain_db};
      camera_clock_ns_ += static_cast<std::uint64_t>(std::llround(
          1e9 * bracketFloorS({&applied_request, 1}, static_cast<double>(frame.image.pixelCount()) *
                                                         sizeof(std::uint16_t))));
      ++frames_taken_;
      frames.push_back(std::move(frame));
    }
    return frames;
  }

  // The scene at the α and under the sun the source gives now (a calibration target has
  // neither); a URI's alpha= stays, and refuses an α that contradicts it; a URI's illuminance=
  // stays too.
  Status showSourceScene() {
    if (!scene_source_ || !options_.calibration_target.empty()) return {};
    const SceneState asked = scene_source_();
    SimulationOptions moved = options_;
    if (asked.alpha_deg && alpha_fixed_) {
      GLARECAM_CHECK(agreesWithUriAlpha(options_.alpha_deg, *asked.alpha_deg));
    } else if (asked.alpha_deg) {
      GLARECAM_ASSIGN(moved.alpha_deg, shownAlphaDeg(*asked.alpha_deg));
    }
    if (asked.source_illuminance_lx && !illuminance_fixed_)
      moved.source_illuminance_lx = *asked.source_illuminance_lx;
    if (moved.alpha_deg == options_.alpha_deg &&
        moved.source_illuminance_lx == options_.source_illuminance_lx)
      return {};
    SimulatedScene scene;
    GLARECAM_ASSIGN(scene, renderSimulatedScene(moved));
    options_ = std::move(moved);
    scene_ = std::move(scene);
    info_.detail = sceneDetail(options_);
    return {};
  }

  // Like a real camera: the exposure is rounded to its resolution and clamped to its range.
  double applied(double exposure_us) const {
    const CameraLimits range = limits();
    return roundedExposureUs(exposure_us, range.exposure_step_us, range.min_exposure_us,
                             range.max_exposure_us);
  }

  SimulationOptions options_;
  SimulatedScene scene_;
  SceneSource scene_source_;
  bool alpha_fixed_ = false;
  bool illuminance_fixed_ = false;
  CameraInfo info_;
  std::uint64_t frames_taken_ = 0;
  std::uint64_t camera_clock_ns_ = 0;  // the simulated camera clock (timestamps)
};

// A calibration target in front of the simulated camera: its lab optics (no ND filter), the
// target's scene, the camera's exact calibration.
Result<SimulatedScene> targetScene(SimulationOptions& sim) {
  CalibrationTargetOptions target;
  GLARECAM_ASSIGN(target.target, parseCalibrationTarget(sim.calibration_target));
  // The camera's own lens, as its calibration states it.
  static_cast<SimulatedCameraModel&>(target) = sim;
  sim.nd_transmission = 1.0;
  SimulatedScene scene;
  GLARECAM_ASSIGN(scene.true_luminance_cd_m2, calibrationTargetScene(target));
  scene.calibration = simulatedCalibration(sim);
  scene.centre_pixel = {(sim.width - 1) / 2.0, (sim.height - 1) / 2.0};
  return scene;
}

class SimCameraBackend final : public CameraBackend {
 public:
  explicit SimCameraBackend(SceneSource scene_source) : scene_source_(std::move(scene_source)) {}

  std::string_view scheme() const override { return "sim"; }

  Result<std::vector<CameraInfo>> list() override {
    return std::vector<CameraInfo>{
        {.uri = "sim:",
         .backend = "sim",
         .vendor = "glarecam",
         .model = "simulated rig",
         .serial = std::string(kSimSerial),
         .detail = "parameters: module, surface, seed, size, fov, alpha, illuminance, target",
         .optics = {}}};
  }

  Result<std::unique_ptr<Camera>> open(std::string_view id, const CameraOptions& options) override {
    if (options.pixel_format && *options.pixel_format != kSimPixelFormat) {
      return badInput(fmt::format("camera URI sim: the simulated camera has {} only, not {}",
                                  kSimPixelFormat, *options.pixel_format));
    }
    // An α beyond the scene's range (a low sun) does not keep the camera from opening: a bracket
    // taken there fails, naming it. One that contradicts the URI's alpha= does.
    const bool alpha_fixed = uriGives(id, "alpha");
    const bool illuminance_fixed = uriGives(id, "illuminance");
    const SceneState asked = scene_source_ ? scene_source_() : SceneState{};
    std::optional<double> asked_deg = asked.alpha_deg;
    if (asked_deg && !alpha_fixed && !shownAlphaDeg(*asked_deg)) asked_deg.reset();
    SimulationOptions sim;
    GLARECAM_ASSIGN(sim, parseSimCameraId(id, asked_deg));
    if (asked.source_illuminance_lx && !illuminance_fixed) {
      sim.source_illuminance_lx = *asked.source_illuminance_lx;
      GLARECAM_CHECK(sim.validate());
    }
    auto rendered = sim.calibration_target.empty() ? renderSimulatedScene(sim) : targetScene(sim);
    if (!rendered) {
      return badInput(fmt::format("camera URI 'sim:{}': {}", id, rendered.error().message));
    }
    return std::make_unique<SimCamera>(std::move(sim), std::move(*rendered),
                                       "sim:" + std::string(id), scene_source_, alpha_fixed,
                                       illuminance_fixed);
  }

 private:
  static bool uriGives(std::string_view id, std::string_view parameter) {
    bool given = false;
    const Status parsed =
        forEachUriParameter(id, kUriName, [&](std::string_view key, std::string_view) -> Status {
          given = given || key == parameter;
          return {};
        });
    return parsed && given;
  }

  SceneSource scene_source_;
};

}  // namespace

std::optional<nlohmann::json> sceneTruthOf(const Camera& camera) {
  const auto* source = dynamic_cast<const SceneTruthSource*>(&camera);
  return source ? source->sceneTruth() : std::nullopt;
}

Result<SimulationOptions> parseSimCameraId(std::string_view id,
                                           std::optional<double> scene_alpha_deg) {
  SimulationOptions sim;
  bool alpha_given = false;
  int scene_keys = 0;  // module= and surface= name the same thing: one of them
  GLARECAM_CHECK(forEachUriParameter(
      id, kUriName, [&](std::string_view key, std::string_view value) -> Status {
        alpha_given = alpha_given || key == "alpha";
        if ((key == "module" || key == "surface") && ++scene_keys > 1)
          return badInput(fmt::format(
              "{} give module= or surface= once: both name what the camera looks at", kUriName));
        return applyParameter(key, value, sim);
      }));
  if (scene_alpha_deg && alpha_given) {
    GLARECAM_CHECK(agreesWithUriAlpha(sim.alpha_deg, *scene_alpha_deg));
  } else if (scene_alpha_deg) {
    GLARECAM_ASSIGN(sim.alpha_deg, shownAlphaDeg(*scene_alpha_deg));
  }
  if (!(sim.alpha_deg >= 0 && sim.alpha_deg <= pipeline::kMaxLimitAlphaDeg)) {
    return badInput(
        fmt::format("camera URI sim: the simulated scene's α must be within 0…{:g}° "
                    "(the method's range), not {:g}",
                    pipeline::kMaxLimitAlphaDeg, sim.alpha_deg));
  }
  return sim;
}

std::unique_ptr<CameraBackend> makeSimCameraBackend(SceneSource scene_source) {
  return std::make_unique<SimCameraBackend>(std::move(scene_source));
}

}  // namespace glarecam::capture
