// glarecam fake-camera: Aravis's GigE Vision fake camera showing the simulated glare scene, until
// Ctrl-C (capture/aravis/fake_gv_camera.h; docs/cameras.md).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "capture/sim/module_model.h"
#include "core/build_config.h"
#include "core/interruption.h"
#if GLARECAM_WITH_ARAVIS
#include "capture/aravis/fake_gv_camera.h"
#endif

namespace glarecam::apps {
namespace {

#if GLARECAM_WITH_ARAVIS
constexpr double kMaxDurationS = 7 * 24 * 3600.0;  // --duration: a week at most

struct FakeCameraArgs {
  capture::FakeGvCameraOptions options;
  std::string size = fmt::format("{}x{}", options.scene.width, options.scene.height);
  std::string seed = "1";
  std::optional<std::string> calibration_out;
  double duration_s = 0;
  std::optional<std::string> module;  // --module NAME: --surface curves:NAME
};

Status runFakeCamera(FakeCameraArgs& args) {
  if (args.module) args.options.scene.surface = std::string(capture::kCurvesPrefix) + *args.module;
  std::pair<int, int> size;
  GLARECAM_ASSIGN(size, parseSize(args.size, "--size"));
  std::tie(args.options.scene.width, args.options.scene.height) = size;
  GLARECAM_ASSIGN(args.options.scene.seed, parseUnsigned(args.seed, "--seed"));
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration_out, "--calibration-out"));
  if (!(args.duration_s >= 0 && args.duration_s <= kMaxDurationS)) {
    return badInput("fake-camera: --duration must be between 0 and 604800 seconds (a week)");
  }
  blockStopSignals();  // before any thread starts, so that only waitForStopSignal() gets them
  std::unique_ptr<capture::FakeGvCamera> camera;
  GLARECAM_ASSIGN(camera, capture::FakeGvCamera::start(args.options));
  if (args.calibration_out) {
    GLARECAM_CHECK(capture::writeFakeCameraFiles(*camera, *args.calibration_out,
                                                 args.options.scene.alpha_deg));
    spdlog::info("fake-camera: calibrations and truth in {}", *args.calibration_out);
  }
  spdlog::info("fake-camera: serving {} on {} (α {:g}°, packet loss {:g}); Ctrl-C stops it",
               camera->uri(), args.options.interface_address, args.options.scene.alpha_deg,
               args.options.packet_loss);
  std::printf("%s\n", camera->uri().c_str());
  std::fflush(stdout);
  waitForStopSignal(args.duration_s);
  return {};
}
#endif

}  // namespace

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
  std::string modules;
  for (const auto& name : capture::moduleNames()) modules += (modules.empty() ? "" : ", ") + name;
  auto* module = sub->add_option("--module", args->module,
                                 "the lobe of a module's empirical curves (" + modules +
                                     "): the same as --surface curves:MODULE");
  sub->add_option(
         "--surface", args->options.scene.surface,
         "what the camera looks at: a physical surface (standard, glare-reduced, gaussian or a "
         "surface FILE.toml, rendered under the sun's disc, truth from its own contours) "
         "or curves:MODULE, the lobe of a module's empirical curves (docs/brdf.md)")
      ->capture_default_str()
      ->excludes(module);
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
