// glarecam calibrate dark: dark frames (lens capped) -> black level, dark frame, hot-pixel map.
#include <memory>

#include "apps/glarecam/calibrate_options.h"

namespace glarecam::apps {
namespace {

Status runDark(const PartArgs& args) {
  return runPart(args, calibration::DarkPartOptions{}, calibration::calibrateDarkPart);
}

}  // namespace

void addCalibrateDarkCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<PartArgs>();
  CLI::App* sub = addPartCommand(
      calibrate, "dark", "dark frames (lens capped) -> black level, dark frame, hot-pixel map",
      *args, false);
  setAction(sub, action, args, runDark);
}

}  // namespace glarecam::apps
