// glarecam capture: bracketed stacks from a camera, on a rig when --config names one
// (daemon/capture_run.h; docs/cameras.md, docs/rig.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "daemon/capture_run.h"

namespace glarecam::apps {
namespace {

constexpr std::uint64_t kMaxFrameRetries = 1000;  // beyond this a link is broken, not lossy

struct CaptureArgs {
  std::optional<std::string> camera, config;
  std::string out;
  std::optional<std::string> alpha, gain, f_number, nd, calibration, pixel_format, module;
  std::optional<std::string> source_illuminance;
  std::string exposures = "auto";
  std::string count = "1";
  double interval_s = 0;
  std::string max_retries = "5";
  bool no_progress = false;
  bool on_button = false;
};

Result<daemon::CaptureRunOptions> runOptions(const CaptureArgs& args) {
  daemon::CaptureRunOptions run;
  run.camera_uri = args.camera;
  if (args.config) run.config_path = *args.config;
  GLARECAM_ASSIGN(run.alpha_deg, parseOptionalNumber(args.alpha, "--alpha"));
  GLARECAM_ASSIGN(run.source_illuminance,
                  parseOptionalSourceIlluminance(args.source_illuminance, "--source-illuminance"));
  std::optional<double> gain;
  GLARECAM_ASSIGN(gain, parseOptionalNumber(args.gain, "--gain"));
  run.capture.gain_db = gain.value_or(0.0);
  GLARECAM_ASSIGN(run.capture.f_number, parseOptionalNumber(args.f_number, "--f-number"));
  GLARECAM_ASSIGN(run.capture.nd_transmission, parseOptionalNumber(args.nd, "--nd-transmission"));
  if (args.exposures != "auto") {
    std::vector<double> exposures;
    GLARECAM_ASSIGN(exposures, parseNumberList(args.exposures, "--exposures", 1, 64));
    run.capture.exposures_us = std::move(exposures);
  }
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration, "--calibration"));
  if (args.calibration) GLARECAM_ASSIGN(run.calibration, readCalibrationFile(*args.calibration));
  run.capture.pixel_format = args.pixel_format;
  if (args.module && args.module->empty()) return badInput("capture: --module must not be empty");
  run.module = args.module;
  std::uint64_t retries = 0;
  GLARECAM_ASSIGN(retries, parseUnsigned(args.max_retries, "--max-retries"));
  if (retries > kMaxFrameRetries) return badInput("capture: --max-retries must be at most 1000");
  run.capture.max_frame_retries = static_cast<int>(retries);
  GLARECAM_ASSIGN(run.series.count, parseUnsigned(args.count, "--count"));
  run.series.interval = std::chrono::duration<double>(args.interval_s);
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  run.series.out = args.out;
  run.series.on_written = [](const std::filesystem::path& written) {
    std::printf("%s\n", written.c_str());
    std::fflush(stdout);
  };
  run.on_button = args.on_button;
  run.show_progress = !args.no_progress;
  return run;
}

Status runCapture(const CaptureArgs& args) {
  daemon::CaptureRunOptions run;
  GLARECAM_ASSIGN(run, runOptions(args));
  return daemon::runCapture(run);
}

}  // namespace

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
  sub->add_option("--source-illuminance", args->source_illuminance,
                  std::string(kSourceIlluminanceHelp) + "; recorded in every stack (origin given)")
      ->option_text("LX[±U]");
  sub->add_option("--exposures", args->exposures,
                  "'auto' (meter, plan, check) or a list of exposure times in µs, e.g. 10,100,1000")
      ->capture_default_str();
  sub->add_option("--gain", args->gain, "analogue gain in dB (default 0)");
  sub->add_option("--module", args->module,
                  "the module measured (name or serial), recorded in each stack; a sweep refuses "
                  "to mix modules (default: the config's [output] module)");
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

}  // namespace glarecam::apps
