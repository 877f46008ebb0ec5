// glarecam calibrate flat: frames of a uniform source -> flat field, 1 at the principal point.
#include <memory>

#include "apps/glarecam/calibrate_options.h"

namespace glarecam::apps {
namespace {

Status runFlat(const PartArgs& args) {
  return runPart(args, calibration::FlatPartOptions{}, calibration::calibrateFlatPart);
}

}  // namespace

void addCalibrateFlatCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<PartArgs>();
  CLI::App* sub = addPartCommand(
      calibrate, "flat", "frames of a uniform source -> flat field, 1 at the principal point",
      *args, true);
  setAction(sub, action, args, runFlat);
}

}  // namespace glarecam::apps
