// glarecam calibrate noise: pairs of flat frames -> read noise and DN per electron.
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "apps/glarecam/calibrate_options.h"

namespace glarecam::apps {
namespace {

struct NoiseArgs {
  PartArgs part;
  std::optional<std::string> roi;
};

Status runNoise(const NoiseArgs& args) {
  calibration::NoisePartOptions options;
  GLARECAM_ASSIGN(options.roi, parseRoiOption(args.roi));
  return runPart(args.part, std::move(options), calibration::calibrateNoisePart);
}

}  // namespace

void addCalibrateNoiseCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<NoiseArgs>();
  CLI::App* sub = addPartCommand(calibrate, "noise",
                                 "pairs of flat frames at several exposures -> read noise and DN "
                                 "per electron (photon transfer curve)",
                                 args->part, true);
  addRoiOption(sub, args->roi);
  setAction(sub, action, args, runNoise);
}

}  // namespace glarecam::apps
