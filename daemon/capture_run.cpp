#include "daemon/capture_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>

#include "capture/camera_registry.h"
#include "capture/sim/sim_camera.h"
#include "core/atomic_file.h"
#include "daemon/daemon_config.h"
#include "daemon/hardware/rig_session.h"

namespace glarecam::daemon {

namespace {

constexpr double kMaxAlphaDeg = 90.0;  // α is measured from the module normal
// A staging directory this old belongs to no capture still running (a bracket takes seconds).
constexpr std::chrono::minutes kStaleTemporaryAge{10};

// The rig of a config: its sensors and GPIO open, α measured once (before the camera opens).
Result<std::unique_ptr<RigSession>> openRig(const CaptureRunOptions& options,
                                            capture::CaptureSettings& settings) {
  const std::filesystem::path& path = *options.config_path;
  Config config;
  GLARECAM_ASSIGN(config, readConfig(path));
  const rig::RigConfig& rig = config.rig;
  if (rig.inclinometer && !rig.site && !rig.fixed_source)
    spdlog::warn(
        "capture: {} has an [inclinometer] but neither [site] nor [source]: α is not "
        "measured",
        path.string());
  if ((rig.site || rig.fixed_source) && options.alpha_deg)
    return badInput(fmt::format("capture: --alpha contradicts {}, whose [{}] gives α; give one",
                                path.string(), rig.site ? "site" : "source"));
  if (options.on_button && !(rig.gpio && rig.gpio->button))
    return badInput(
        fmt::format("capture: --on-button, but {} has no [gpio] button line", path.string()));
  auto session = std::make_unique<RigSession>(
      config.rig, RigSessionOptions{.faults = config.daemon.faults,
                                    .log_name = "capture",
                                    .show_progress = options.show_progress,
                                    .on_button = options.on_button});
  GLARECAM_CHECK(session->openSensors());
  GLARECAM_CHECK(session->openGpio());
  GLARECAM_CHECK(session->openIlluminance());
  if (!options.calibration) GLARECAM_ASSIGN(settings.calibration, session->cameraCalibration());
  if (!options.module && config.daemon.output.module != kUnnamedModule)
    settings.module = config.daemon.output.module;
  if (!session->measuresAlpha()) return session;
  // With the button, each press measures again, so a rig still moving now only warns.
  const auto measured = session->measure(utcNow(), sun::systemClockStatus());
  if (!measured && !(options.on_button && measured.error().code == ErrorCode::kHardware))
    return std::unexpected(measured.error());
  if (!measured) {
    spdlog::warn("capture: {}", measured.error().message);
    return session;
  }
  spdlog::info("capture: α {:.3f}° ± {:.3f}° (module tilt {:.3f}°)", measured->alpha_deg,
               measured->alpha_uncertainty_deg, measured->module.tilt_deg);
  RigSession::record(measured, settings);
  return session;
}

}  // namespace

Status CaptureRunOptions::validate() const {
  if (alpha_deg && !(*alpha_deg >= 0 && *alpha_deg < kMaxAlphaDeg))
    return badInput("capture: --alpha must be in [0, 90) degrees");
  if (capture.f_number && !(*capture.f_number > 0))
    return badInput("capture: --f-number must be positive");
  if (capture.nd_transmission && !(*capture.nd_transmission > 0 && *capture.nd_transmission <= 1))
    return badInput("capture: --nd-transmission must be in (0, 1]");
  if (on_button && !config_path)
    return badInput("capture: --on-button needs a --config with a [gpio] button line");
  return series.validate();
}

Status checkAgainstCamera(const capture::Camera& camera, const capture::CaptureSettings& settings) {
  const capture::CameraOptics& known = camera.info().optics;
  if ((settings.optics.f_number && known.f_number) ||
      (settings.optics.nd_transmission && known.nd_transmission)) {
    return badInput(
        fmt::format("capture: {} knows its own lens and filter; --f-number and "
                    "--nd-transmission are for real cameras",
                    camera.info().uri));
  }
  if (!settings.calibration && !camera.info().calibration) {
    spdlog::warn(
        "capture: no --calibration; the stacks need one when processed "
        "(glarecam process --calibration FILE)");
  }
  if (!settings.alpha_deg && !capture::sceneTruthOf(camera)) {
    spdlog::warn(
        "capture: no --alpha; the stacks record no angle of incidence, so process "
        "cannot apply the α-dependent glare limit");
  }
  return {};
}

Status runCapture(const CaptureRunOptions& options) {
  GLARECAM_CHECK(options.validate());
  capture::CaptureSettings settings = capture::captureSettings(options.capture);
  settings.alpha_deg = options.alpha_deg;
  settings.calibration = options.calibration;
  settings.module = options.module;
  // Given, else the lab lamp's as the config states it.
  settings.source_illuminance = options.source_illuminance;
  settings.show_progress = options.show_progress;
  std::unique_ptr<RigSession> rig;
  if (options.config_path) GLARECAM_ASSIGN(rig, openRig(options, settings));
  if (rig) {
    // A rig measures α and knows its source's E (a lamp the config states), or leaves them
    // unknown: a simulated camera's scene never stands in for them.
    settings.alpha_from_scene = !rig->measuresAlpha();
    if (!settings.source_illuminance)
      settings.source_illuminance = rig->config().fixed_source_illuminance;
  }
  std::string camera_uri = options.camera_uri.value_or("");
  if (!options.camera_uri && rig && rig->config().camera) camera_uri = *rig->config().camera;
  if (camera_uri.empty())
    return badInput("capture: give --camera URI (or a --config with camera = \"URI\")");
  const std::filesystem::path& out = options.series.out;
  std::error_code error;
  if (std::filesystem::exists(out, error) && !std::filesystem::is_directory(out, error))
    return badInput(fmt::format("capture: --out {} is not a directory", out.string()));
  // A capture killed while writing leaves its hidden staging directory: old ones go now.
  if (std::filesystem::is_directory(out, error)) removeStaleTemporaries(out, kStaleTemporaryAge);
  // The α the rig measured for this stack; else the --alpha given (a config without [site]).
  // The sun that lights a simulated scene: the rig's clear-sky sun, else the one given.
  const capture::SceneSource scene_source = [&rig, given = options.alpha_deg,
                                             source = options.source_illuminance] {
    capture::SceneState state = rig ? rig->sceneState() : capture::SceneState{};
    if (!state.alpha_deg) state.alpha_deg = given;
    if (source) state.source_illuminance_lx = source->illuminance_lx;
    return state;
  };
  std::unique_ptr<capture::Camera> camera;
  GLARECAM_ASSIGN(camera, capture::openCamera(camera_uri, capture::cameraOptions(options.capture),
                                              scene_source));
  GLARECAM_CHECK(checkAgainstCamera(*camera, settings));
  return capture::captureSeries(*camera, std::move(settings), options.series, rig.get());
}

}  // namespace glarecam::daemon
