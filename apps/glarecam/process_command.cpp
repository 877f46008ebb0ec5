// glarecam process: one stack -> luminance.exr, luminance.png, result.json (docs/process.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/json.h"
#include "pipeline/process_stack.h"
#include "sun/clear_sky.h"

namespace glarecam::apps {
namespace {

constexpr const char* kClearSkyWord = "clear-sky";

struct ProcessArgs {
  std::string stack;
  // Optional, so that a given but empty value ("--threshold $UNSET") is an error, not a default.
  std::optional<std::string> calibration, out, threshold, thresholds, alpha, source_illuminance,
      reference_illuminance;
  bool json = false, no_progress = false, force_calibration = false, float32 = false,
       no_ladder = false;
  unsigned threads = 0;
  double max_calibration_age_days = 365;
};

Status runProcess(const ProcessArgs& args) {
  if (args.stack.empty()) return badInput("STACK: expected a stack directory, got an empty string");
  pipeline::ProcessOptions options;
  GLARECAM_CHECK(requireNonEmptyPath(args.calibration, "--calibration"));
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  if (args.calibration) options.calibration_file = *args.calibration;
  if (args.out) options.output_directory = *args.out;
  options.threads = args.threads;
  GLARECAM_ASSIGN(options.threshold_cd_m2, parseOptionalNumber(args.threshold, "--threshold"));
  GLARECAM_ASSIGN(options.alpha_deg, parseOptionalNumber(args.alpha, "--alpha"));
  if (args.source_illuminance == kClearSkyWord) {
    options.estimate_source = sun::clearSkySourceOfStack;
  } else {
    GLARECAM_ASSIGN(
        options.source_illuminance,
        parseOptionalSourceIlluminance(args.source_illuminance, "--source-illuminance"));
  }
  GLARECAM_ASSIGN(options.reference_illuminance_lx,
                  parseReferenceIlluminance(args.reference_illuminance, "--reference-illuminance"));
  if (args.thresholds) {
    auto thresholds =
        parseNumberList(*args.thresholds, "--thresholds", 1, pipeline::kMaxThresholds);
    if (!thresholds) return std::unexpected(thresholds.error());
    options.thresholds_cd_m2 = *thresholds;
  }
  options.show_progress = !args.no_progress;
  options.float32 = args.float32;
  options.ladder = !args.no_ladder;
  if (!(args.max_calibration_age_days > 0))
    return badInput("--max-calibration-age-days must be positive");
  options.calibration_use = {.force = args.force_calibration,
                             .max_age_days = args.max_calibration_age_days};
  auto summary = pipeline::processStack(args.stack, options);
  if (!summary) return std::unexpected(summary.error());
  spdlog::info("{}", summary->briefReport());
  if (args.json) {
    std::printf("%s", jsonText(pipeline::toJson(summary->result)).c_str());
  } else {
    std::printf("%s\n", summary->output_directory.c_str());
  }
  return {};
}

}  // namespace

void addProcessCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<ProcessArgs>();
  CLI::App* sub = app.add_subcommand(
      "process",
      "Turn a stack into a luminance image, glare ellipses and result.json (docs/process.md)");
  sub->add_option("STACK", args->stack, "stack directory (holding stack.json)")->required();
  sub->add_option("--calibration", args->calibration,
                  "calibration JSON file; overrides the stack's");
  sub->add_option("--out", args->out, "output directory (default STACK/result)");
  sub->add_option("--alpha", args->alpha,
                  "angle of incidence α in degrees for a stack that records none (recorded in "
                  "result.json as given); one that contradicts the stack's is refused");
  sub->add_option("--source-illuminance", args->source_illuminance,
                  std::string(kSourceIlluminanceHelp) +
                      "; replaces the stack's own `source`. `clear-sky`: for a stack that records "
                      "no source, the clear-sky estimate for the sun its rig measured (origin "
                      "clear_sky, 15-30 % uncertain)")
      ->option_text("LX[±U]|clear-sky");
  sub->add_option("--reference-illuminance", args->reference_illuminance, kReferenceIlluminanceHelp)
      ->option_text("LX");
  sub->add_option("--threshold", args->threshold,
                  "constant glare limit in cd/m² instead of the α curve (e.g. 30000)");
  sub->add_option("--thresholds", args->thresholds,
                  "extra ellipse levels in cd/m², comma-separated, at most 32 (threshold sweep)");
  sub->add_flag("--no-ladder", args->no_ladder,
                "no contour ladder: result.json's `contours` is null (a little faster)");
  sub->add_flag("--force-calibration", args->force_calibration,
                "use a calibration made for another camera serial than the stack's");
  sub->add_option("--max-calibration-age-days", args->max_calibration_age_days,
                  "warn about calibration parts older than this (default 365)");
  sub->add_flag("--json", args->json, "print result.json on stdout");
  sub->add_option("--threads", args->threads,
                  "threads in all, every step keeping to them; 1 starts none (default: all cores)");
  sub->add_flag("--float32", args->float32,
                "luminance.exr and quality.exr in lossless float32 (larger; default: luminance to "
                "a relative 1.5e-5, the uncertainty as half)");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runProcess(*args); }; });
}

}  // namespace glarecam::apps
