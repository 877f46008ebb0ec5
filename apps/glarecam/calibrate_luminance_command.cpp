// glarecam calibrate luminance: a stack of a reference surface the luminance meter measured -> K
// with its uncertainty; with --check, an in-scene reference against an existing K (drift,
// calibration/luminance_drift.h).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apps/glarecam/calibrate_options.h"
#include "calibration/luminance_drift.h"
#include "core/json.h"

namespace glarecam::apps {
namespace {

struct LuminanceArgs {
  PartArgs part;
  std::optional<std::string> roi, log;
  std::vector<double> references_cd_m2;
  double meter_accuracy_percent = calibration::kDefaultMeterAccuracyPercent;
  bool check = false;
};

Status runCheck(const LuminanceArgs& args, const std::optional<calibration::Roi>& roi,
                const calibration::LuminanceReference& reference) {
  calibration::DriftCheckOptions options;
  // The check reads recorded field stacks only: with --camera it has none.
  if (!args.part.camera) options.stacks = args.part.stacks;
  options.calibrations = args.part.calibrations;
  options.roi = roi;
  options.reference = reference;
  if (args.log) options.log = *args.log;
  options.show_progress = !args.part.no_progress;
  calibration::DriftReport report;
  GLARECAM_ASSIGN(report, calibration::checkLuminanceDrift(options));
  if (args.part.json) {
    std::printf("%s", jsonText(report.toJson()).c_str());
  } else {
    std::printf("K %.6g, measured %.6g: drift %+.2f %% (u %.2f %%)\n", report.luminance_factor,
                report.measured_luminance_factor, 100 * report.drift, 100 * report.drift_u);
  }
  return report.verdict();
}

Status runLuminance(const LuminanceArgs& args) {
  calibration::LuminanceReference reference;
  reference.readings_cd_m2 = args.references_cd_m2;
  reference.meter_accuracy_percent = args.meter_accuracy_percent;
  std::optional<calibration::Roi> roi;
  GLARECAM_ASSIGN(roi, parseRoiOption(args.roi));
  if (args.check) return runCheck(args, roi, reference);
  calibration::LuminancePartOptions options;
  options.roi = roi;
  options.reference = std::move(reference);
  return runPart(args.part, std::move(options), calibration::calibrateLuminancePart);
}

}  // namespace

void addCalibrateLuminanceCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<LuminanceArgs>();
  CLI::App* sub =
      addPartCommand(calibrate, "luminance",
                     "a stack of a reference surface measured with a luminance meter -> K with its "
                     "uncertainty; --check: an in-scene reference against an existing K (drift)",
                     args->part, true);
  addRoiOption(sub, args->roi);
  sub->add_option("--reference", args->references_cd_m2,
                  "the meter's reading in cd/m²; repeat for several readings")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--meter-accuracy", args->meter_accuracy_percent,
                  "the meter's stated accuracy, ± percent (default 2)");
  sub->add_flag("--check", args->check,
                "check the --calibration's K for drift instead of writing a part");
  sub->add_option("--log", args->log, "with --check: CSV file the check's line is appended to");
  setAction(sub, action, args, runLuminance);
}

}  // namespace glarecam::apps
