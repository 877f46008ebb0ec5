// glarecam cameras / capture / fake-camera: the camera backends (capture/camera_registry.h), the
// bracketer (capture/bracketer.h) and Aravis's GigE Vision fake camera showing our scene.
#include <fmt/format.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <memory>
#include <optional>
#include <thread>

#include "apps/glarecam/capture_rig.h"
#include "apps/glarecam/commands.h"
#include "apps/glarecam/interruption.h"
#include "apps/glarecam/option_parsing.h"
#include "capture/bracketer.h"
#include "capture/camera_registry.h"
#include "capture/capture_config.h"
#include "capture/sim/sim_camera.h"
#include "core/atomic_file.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "core/time.h"
#if GLARECAM_WITH_ARAVIS
#include "capture/aravis/fake_gv_camera.h"
#endif

namespace glarecam::apps {
namespace {

constexpr double kMaxAlphaDeg = 90.0;             // α is measured from the module normal
constexpr std::uint64_t kMaxFrameRetries = 1000;  // beyond this a link is broken, not lossy
constexpr double kMaxWaitS = 7 * 24 * 3600.0;     // --interval, --duration: a week at most
// A staging directory this old belongs to no capture still running (a bracket takes seconds).
constexpr std::chrono::minutes kStaleTemporaryAge{10};

// ---- cameras -------------------------------------------------------------------------------

nlohmann::json cameraInfoJson(const capture::CameraInfo& camera) {
  return {{"uri", camera.uri},     {"backend", camera.backend}, {"vendor", camera.vendor},
          {"model", camera.model}, {"serial", camera.serial},   {"detail", camera.detail}};
}

Status runCameras(bool json) {
  nlohmann::json document = {{"cameras", nlohmann::json::array()},
                             {"unavailable", nlohmann::json::object()}};
  for (const auto& backend : capture::cameraBackends()) {
    auto cameras = backend->list();
    if (!cameras) {
      document["unavailable"][std::string(backend->scheme())] = cameras.error().message;
      if (!json)
        std::printf("%s: %s\n", std::string(backend->scheme()).c_str(),
                    cameras.error().message.c_str());
      continue;
    }
    for (const auto& camera : *cameras) {
      document["cameras"].push_back(cameraInfoJson(camera));
      if (!json) {
        std::printf("%-28s %s %s (serial %s) %s\n", camera.uri.c_str(), camera.vendor.c_str(),
                    camera.model.c_str(), camera.serial.empty() ? "-" : camera.serial.c_str(),
                    camera.detail.c_str());
      }
    }
  }
  if (json) std::fputs(jsonText(document).c_str(), stdout);
  return {};
}

// ---- capture -------------------------------------------------------------------------------

struct CaptureArgs {
  std::optional<std::string> camera, config;
  std::string out;
  std::optional<std::string> alpha, gain, f_number, nd, calibration, pixel_format;
  std::string exposures = "auto";
  std::string count = "1";
  double interval_s = 0;
  std::string max_retries = "5";
  bool no_progress = false;
  bool on_button = false;
};

Result<capture::CaptureSettings> captureSettings(const CaptureArgs& args) {
  capture::CaptureSettings settings;
  GLARECAM_ASSIGN(settings.alpha_deg, parseOptionalNumber(args.alpha, "--alpha"));
  if (settings.alpha_deg && !(*settings.alpha_deg >= 0 && *settings.alpha_deg < kMaxAlphaDeg)) {
    return badInput("capture: --alpha must be in [0, 90) degrees");
  }
  std::optional<double> gain;
  GLARECAM_ASSIGN(gain, parseOptionalNumber(args.gain, "--gain"));
  settings.gain_db = gain.value_or(0.0);
  GLARECAM_ASSIGN(settings.optics.f_number, parseOptionalNumber(args.f_number, "--f-number"));
  GLARECAM_ASSIGN(settings.optics.nd_transmission,
                  parseOptionalNumber(args.nd, "--nd-transmission"));
  if (settings.optics.f_number && !(*settings.optics.f_number > 0)) {
    return badInput("capture: --f-number must be positive");
  }
  if (settings.optics.nd_transmission &&
      !(*settings.optics.nd_transmission > 0 && *settings.optics.nd_transmission <= 1)) {
    return badInput("capture: --nd-transmission must be in (0, 1]");
  }
  if (args.exposures != "auto") {
    std::vector<double> exposures;
    GLARECAM_ASSIGN(exposures, parseNumberList(args.exposures, "--exposures", 1, 64));
    settings.exposures_us = std::move(exposures);
  }
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration, "--calibration"));
  if (args.calibration) {
    GLARECAM_ASSIGN(settings.calibration, readCalibrationFile(*args.calibration));
  }
  settings.show_progress = !args.no_progress;
  return settings;
}

Result<capture::CameraOptions> cameraOptions(const CaptureArgs& args) {
  capture::CaptureConfig config;
  config.pixel_format = args.pixel_format;
  std::uint64_t retries = 0;
  GLARECAM_ASSIGN(retries, parseUnsigned(args.max_retries, "--max-retries"));
  if (retries > kMaxFrameRetries) return badInput("capture: --max-retries must be at most 1000");
  config.max_frame_retries = static_cast<int>(retries);
  return capture::cameraOptions(config);
}

Status checkAgainstCamera(const capture::Camera& camera, const capture::CaptureSettings& settings);
Status captureSeries(capture::Camera& camera, capture::CaptureSettings settings, CaptureRig* rig,
                     const std::string& out, std::uint64_t count, double interval_s);

Status runCapture(const CaptureArgs& args) {
  capture::CaptureSettings settings;
  GLARECAM_ASSIGN(settings, captureSettings(args));
  std::string camera_uri = args.camera.value_or("");
  std::unique_ptr<CaptureRig> rig;
  if (args.config) {
    GLARECAM_ASSIGN(rig, CaptureRig::open(*args.config, args.alpha.has_value(), args.on_button,
                                          !args.no_progress));
    if (!args.camera && rig->config().camera) camera_uri = *rig->config().camera;
    if (!args.calibration) GLARECAM_ASSIGN(settings.calibration, rig->cameraCalibration());
    // The scene a simulated camera renders needs α before the camera opens. With the button,
    // each press measures again, so a rig still moving now only warns.
    if (rig->measuresAlpha()) {
      const Status measured = rig->measureInto(settings);
      if (!measured && !(args.on_button && measured.error().code == ErrorCode::kHardware))
        return measured;
      if (!measured) spdlog::warn("capture: {}", measured.error().message);
    }
  } else if (args.on_button) {
    return badInput("capture: --on-button needs a --config with a [gpio] button line");
  }
  if (camera_uri.empty())
    return badInput("capture: give --camera URI (or a --config with camera = \"URI\")");
  capture::CameraOptions options;
  GLARECAM_ASSIGN(options, cameraOptions(args));
  std::uint64_t count = 0;
  GLARECAM_ASSIGN(count, parseUnsigned(args.count, "--count"));
  if (count == 0) return badInput("capture: --count must be at least 1");
  if (!(args.interval_s >= 0 && args.interval_s <= kMaxWaitS)) {
    return badInput("capture: --interval must be between 0 and 604800 seconds (a week)");
  }
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  std::error_code error;
  if (std::filesystem::exists(args.out, error) && !std::filesystem::is_directory(args.out, error)) {
    return badInput(fmt::format("capture: --out {} is not a directory", args.out));
  }
  // A capture killed while writing leaves its hidden staging directory: old ones go now.
  if (std::filesystem::is_directory(args.out, error)) {
    removeStaleTemporaries(args.out, kStaleTemporaryAge);
  }
  std::unique_ptr<capture::Camera> camera;
  GLARECAM_ASSIGN(camera, capture::openCamera(camera_uri, options,
                                              [alpha = settings.alpha_deg] { return alpha; }));
  GLARECAM_CHECK(checkAgainstCamera(*camera, settings));
  return captureSeries(*camera, std::move(settings), rig.get(), args.out, count, args.interval_s);
}

// What the camera itself knows must not be contradicted, and what it lacks is warned about.
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

// Before each stack of a series with a rig: the operator's press when asked for, and the
// geometry (the first stack's was measured before the camera opened, unless a press came since).
// With the button, an inclinometer that cannot read (the rig moving in a gust) shows its fault
// code and waits for the next press instead of ending the session.
Result<bool> prepareRigStack(CaptureRig& rig, capture::CaptureSettings& settings, bool first) {
  for (;;) {
    bool pressed = false;
    GLARECAM_ASSIGN(pressed, rig.waitForButton());
    if (!pressed) return false;
    if (!rig.measuresAlpha() || (first && !rig.waitsForButton())) break;
    const Status measured = rig.measureInto(settings);
    if (measured) break;
    if (!rig.waitsForButton() || measured.error().code != ErrorCode::kHardware)
      return std::unexpected(measured.error());
    spdlog::error("capture: {}; press the button to try again", measured.error().message);
    rig.showFault(rig::FaultCode::kInclinometer);
  }
  rig.showCapturing(true);
  return true;
}

Status captureSeries(capture::Camera& camera, capture::CaptureSettings settings, CaptureRig* rig,
                     const std::string& out, std::uint64_t count, double interval_s) {
  stopGracefullyOnSignals();
  auto next = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < count; ++i) {
    sleepUntil(next);
    const auto interrupted = [&] {
      return fail(ErrorCode::kInternal,
                  fmt::format("capture: interrupted after {} of {} stacks", i, count));
    };
    if (stopRequested()) return interrupted();
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(interval_s));
    if (rig) {
      bool go = false;
      GLARECAM_ASSIGN(go, prepareRigStack(*rig, settings, i == 0));
      if (!go) return interrupted();  // stopped while waiting for the button
    }
    capture::CapturedStack stack;
    const UtcTime bracket_start = utcNow();
    GLARECAM_ASSIGN(stack, capture::captureStack(camera, settings));
    if (rig) {
      rig->showCapturing(false);
      rig->finishStack(stack, bracket_start, utcNow());
    }
    std::filesystem::path written;
    GLARECAM_ASSIGN(written, capture::writeCapturedStack(out, stack));
    std::printf("%s\n", written.c_str());
    std::fflush(stdout);
  }
  return {};
}

// ---- fake-camera ---------------------------------------------------------------------------

#if GLARECAM_WITH_ARAVIS
struct FakeCameraArgs {
  capture::FakeGvCameraOptions options;
  std::string size = fmt::format("{}x{}", options.scene.width, options.scene.height);
  std::string seed = "1";
  std::optional<std::string> calibration_out;
  double duration_s = 0;
};

// The calibrations of both pixel formats and the scene's truth, for checking captures.
Status writeFakeCameraFiles(const capture::FakeGvCamera& camera, const std::string& directory,
                            double alpha_deg) {
  GLARECAM_CHECK(ensureDirectory(directory));
  for (const auto& [format, file] : {std::pair{"Mono16", "fake-camera-mono16.json"},
                                     std::pair{"Mono8", "fake-camera-mono8.json"}}) {
    Calibration calibration;
    GLARECAM_ASSIGN(calibration, camera.calibration(format));
    GLARECAM_CHECK(
        writeFileAtomic(std::filesystem::path(directory) / file, jsonText(toJson(calibration))));
  }
  GLARECAM_CHECK(writeFileAtomic(std::filesystem::path(directory) / "fake-camera-truth.json",
                                 jsonText(capture::sceneTruthJson(camera.scene(), alpha_deg))));
  spdlog::info("fake-camera: calibrations and truth in {}", directory);
  return {};
}

sigset_t stopSignals() {
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  return stop;
}

// Blocks until SIGINT / SIGTERM (blocked in every thread, see runFakeCamera), or for
// `duration_s` when positive.
void waitForStop(double duration_s) {
  const sigset_t stop = stopSignals();
  if (duration_s > 0) {
    const auto whole = static_cast<time_t>(duration_s);
    const timespec timeout{whole, static_cast<long>((duration_s - whole) * 1e9)};
    sigtimedwait(&stop, nullptr, &timeout);
  } else {
    int signal_number = 0;
    sigwait(&stop, &signal_number);
  }
}

Status runFakeCamera(FakeCameraArgs& args) {
  std::pair<int, int> size;
  GLARECAM_ASSIGN(size, parseSize(args.size, "--size"));
  std::tie(args.options.scene.width, args.options.scene.height) = size;
  GLARECAM_ASSIGN(args.options.scene.seed, parseUnsigned(args.seed, "--seed"));
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration_out, "--calibration-out"));
  if (!(args.duration_s >= 0 && args.duration_s <= kMaxWaitS)) {
    return badInput("fake-camera: --duration must be between 0 and 604800 seconds (a week)");
  }
  // Block the stop signals before any thread starts, so that only waitForStop receives them.
  const sigset_t stop = stopSignals();
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  std::unique_ptr<capture::FakeGvCamera> camera;
  GLARECAM_ASSIGN(camera, capture::FakeGvCamera::start(args.options));
  if (args.calibration_out) {
    GLARECAM_CHECK(
        writeFakeCameraFiles(*camera, *args.calibration_out, args.options.scene.alpha_deg));
  }
  spdlog::info("fake-camera: serving {} on {} (α {:g}°, packet loss {:g}); Ctrl-C stops it",
               camera->uri(), args.options.interface_address, args.options.scene.alpha_deg,
               args.options.packet_loss);
  std::printf("%s\n", camera->uri().c_str());
  std::fflush(stdout);
  waitForStop(args.duration_s);
  return {};
}
#endif

}  // namespace

void addCamerasCommand(CLI::App& app, Action& action) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub =
      app.add_subcommand("cameras",
                         "List the cameras every backend can see: sim, aravis, libcamera, v4l2 "
                         "(docs/cameras.md)");
  sub->add_flag("--json", *json, "print JSON instead of a table");
  sub->callback([json, &action] { action = [json] { return runCameras(*json); }; });
}

void addCaptureCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<CaptureArgs>();
  CLI::App* sub = app.add_subcommand(
      "capture",
      "Capture a bracketed stack from a camera and write it atomically under --out; "
      "prints each stack's path (docs/cameras.md)");
  sub->add_option("--camera", args->camera,
                  "camera URI: sim:[KEY=VALUE,...], aravis:[ID], libcamera:[ID], v4l2:/dev/videoN "
                  "(default: the --config's)");
  sub->add_option("--config", args->config,
                  "rig config (TOML, docs/rig.md): camera, calibration, and the inclinometer, "
                  "site and module that give α and the manifest's geometry block");
  sub->add_option("--out", args->out, "directory the stacks are written into (created)")
      ->required();
  sub->add_option("--alpha", args->alpha, "angle of incidence α in degrees, recorded in the stack");
  sub->add_option("--exposures", args->exposures,
                  "'auto' (meter, plan, check) or a list of exposure times in µs, e.g. 10,100,1000")
      ->capture_default_str();
  sub->add_option("--gain", args->gain, "analogue gain in dB (default 0)");
  sub->add_option("--calibration", args->calibration,
                  "calibration file written inline into each stack; its black level and "
                  "saturation guide the auto-bracket");
  sub->add_option("--pixel-format", args->pixel_format,
                  "pixel format: Mono16, Mono12, Mono8 (Mono10 with v4l2, libcamera's names "
                  "with libcamera); default the deepest mono one");
  sub->add_option("--f-number", args->f_number, "lens f-number, when the camera cannot know it");
  sub->add_option("--nd-transmission", args->nd, "ND filter transmission in (0, 1]");
  sub->add_option("--count", args->count, "number of stacks in the series")->capture_default_str();
  sub->add_option("--interval", args->interval_s, "seconds from one capture's start to the next")
      ->capture_default_str();
  sub->add_option("--max-retries", args->max_retries,
                  "incomplete or timed-out frames retried per exposure")
      ->capture_default_str();
  sub->add_flag("--on-button", args->on_button,
                "wait for the operator's button (the --config's [gpio]) before each stack");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runCapture(*args); }; });
}

void addFakeCameraCommand(CLI::App& app, Action& action) {
#if GLARECAM_WITH_ARAVIS
  auto args = std::make_shared<FakeCameraArgs>();
  CLI::App* sub = app.add_subcommand(
      "fake-camera",
      "Serve Aravis's GigE Vision fake camera showing the simulated glare scene; prints its URI "
      "and runs until Ctrl-C (docs/cameras.md)");
  sub->add_option("--interface", args->options.interface_address,
                  "network interface name or IPv4 address to serve on")
      ->capture_default_str();
  sub->add_option("--serial", args->options.serial, "the camera's serial number")
      ->capture_default_str();
  sub->add_option("--alpha", args->options.scene.alpha_deg, "α of the scene, degrees 0..80")
      ->capture_default_str();
  sub->add_option("--module", args->options.scene.module, "module glare model")
      ->capture_default_str();
  sub->add_option("--size", args->size, "frame size WIDTHxHEIGHT (at most 2048x2048)")
      ->capture_default_str();
  sub->add_option("--fov", args->options.scene.horizontal_fov_deg,
                  "horizontal field of view in degrees")
      ->capture_default_str();
  sub->add_option("--seed", args->seed, "noise seed")->capture_default_str();
  sub->add_option("--packet-loss", args->options.packet_loss,
                  "fraction of GVSP packets dropped, e.g. 0.001")
      ->capture_default_str();
  sub->add_option("--calibration-out", args->calibration_out,
                  "directory to write the calibrations (fake-camera-mono16.json, "
                  "fake-camera-mono8.json) and the scene's truth (fake-camera-truth.json) into");
  sub->add_option("--duration", args->duration_s,
                  "stop after this many seconds (0: run until "
                  "SIGINT/SIGTERM)")
      ->capture_default_str();
  sub->callback([args, &action] { action = [args] { return runFakeCamera(*args); }; });
#else
  app.add_subcommand("fake-camera", "Unavailable: this glarecam was built without Aravis 0.8")
      ->callback([&action] {
        action = [] {
          return hardwareError("fake-camera: this glarecam was built without Aravis 0.8");
        };
      });
#endif
}

}  // namespace glarecam::apps
