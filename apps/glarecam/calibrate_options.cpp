#include "apps/glarecam/calibrate_options.h"

#include <cstdio>
#include <filesystem>

#include "apps/glarecam/option_parsing.h"
#include "capture/calibration_series.h"
#include "core/json.h"

namespace glarecam::apps {

CLI::App* addPartCommand(CLI::App& calibrate, const std::string& name, const std::string& help,
                         PartArgs& args, bool reads_prior) {
  CLI::App* sub = calibrate.add_subcommand(name, help);
  sub->add_option("STACK", args.stacks, "calibration stacks (glarecam.stack/1)");
  sub->add_option("--camera", args.camera,
                  "capture the stack with this camera instead (saved as <out>-stacks/)");
  sub->add_option("--exposures", args.exposures,
                  "with --camera: exposures in µs, comma-separated; repeat a value for several "
                  "frames (e.g. 1000,1000,10000,10000)");
  sub->add_option("--gain-db", args.gain_db, "with --camera: analogue gain (default 0)");
  sub->add_option("--out", args.out,
                  "the part's glarecam.calibration/1 file (its images go beside it)");
  if (reads_prior) {
    sub->add_option("--calibration", args.calibrations,
                    "earlier parts (black level, saturation, ...), repeatable, merged in order; "
                    "default: the stack's calibration block")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  }
  sub->add_flag("--json", args.json, "print the written file on stdout");
  sub->add_flag("--no-progress", args.no_progress, "no progress on stderr");
  return sub;
}

void addRoiOption(CLI::App* sub, std::optional<std::string>& roi) {
  sub->add_option("--roi", roi, "region x,y,w,h in pixels (default: the central quarter)");
}

Result<std::optional<calibration::Roi>> parseRoiOption(const std::optional<std::string>& roi) {
  if (!roi) return std::optional<calibration::Roi>{};
  calibration::Roi parsed;
  GLARECAM_ASSIGN(parsed, calibration::parseRoi(*roi, "--roi"));
  return std::optional(parsed);
}

Result<calibration::PartInputs> partInputs(const PartArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  calibration::PartInputs inputs;
  inputs.stacks = args.stacks;
  inputs.calibrations = args.calibrations;
  inputs.out = args.out.value_or("");
  inputs.show_progress = !args.no_progress;
  return inputs;
}

Status captureStacks(const PartArgs& args, calibration::PartInputs& inputs) {
  if (args.camera.has_value() == !args.stacks.empty())
    return badInput("give the calibration stacks (STACK...) or --camera URI to capture them");
  if (!args.camera) return {};
  if (!args.exposures)
    return badInput("--camera needs --exposures LIST (µs; repeat a value for several frames)");
  capture::CalibrationSeriesOptions series;
  series.camera_uri = *args.camera;
  GLARECAM_ASSIGN(series.exposures_us,
                  parseNumberList(*args.exposures, "--exposures", 1, capture::kMaxSeriesFrames));
  series.gain_db = args.gain_db;
  series.views = args.views;
  series.view_interval_s = args.view_interval_s;
  series.directory = calibration::companionFile(inputs.out, "-stacks");
  series.show_progress = !args.no_progress;
  std::vector<std::filesystem::path> captured;
  GLARECAM_ASSIGN(captured, capture::captureCalibrationSeries(series));
  for (const std::filesystem::path& stack : captured) inputs.stacks.push_back(stack.string());
  return {};
}

void printPart(const calibration::PartReport& report, bool as_json) {
  if (as_json) {
    std::printf("%s", jsonText(calibration::toJson(report.document)).c_str());
    return;
  }
  std::printf("%s: %s\n", report.part.c_str(), report.method.c_str());
  for (const auto& [key, value] : report.document.values.items()) {
    if (value.is_object() || value.is_array()) continue;
    std::printf("  %s = %s\n", key.c_str(), value.dump().c_str());
  }
  std::printf("%s\n", report.file.c_str());
}

}  // namespace glarecam::apps
