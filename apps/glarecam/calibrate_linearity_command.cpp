// glarecam calibrate linearity: a ramp of exposures of a steady source -> deviation from linear,
// usable range, saturation_dn.
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "apps/glarecam/calibrate_options.h"

namespace glarecam::apps {
namespace {

struct LinearityArgs {
  PartArgs part;
  std::optional<std::string> roi;
  double tolerance_percent = 100 * calibration::kDefaultLinearityTolerance;
};

Status runLinearity(const LinearityArgs& args) {
  calibration::LinearityPartOptions options;
  GLARECAM_ASSIGN(options.roi, parseRoiOption(args.roi));
  options.tolerance_percent = args.tolerance_percent;
  return runPart(args.part, std::move(options), calibration::calibrateLinearityPart);
}

}  // namespace

void addCalibrateLinearityCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<LinearityArgs>();
  CLI::App* sub =
      addPartCommand(calibrate, "linearity",
                     "a ramp of exposures of a steady source -> deviation from linear, usable "
                     "range, saturation_dn",
                     args->part, true);
  addRoiOption(sub, args->roi);
  sub->add_option("--tolerance-percent", args->tolerance_percent,
                  "deviation from linear that ends the usable range (default 1)");
  setAction(sub, action, args, runLinearity);
}

}  // namespace glarecam::apps
