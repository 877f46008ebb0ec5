// glarecam calibrate dark|flat|linearity|noise|luminance|intrinsics|merge: measured calibration
// parts as glarecam.calibration/1 files (docs/calibration.md). Each subcommand is in its own
// calibrate_*_command.cpp; calibration/calibration_parts.h measures and writes the parts.
#include "apps/glarecam/calibrate_options.h"
#include "apps/glarecam/commands.h"

namespace glarecam::apps {

void addCalibrateCommand(CLI::App& app, Action& action) {
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Measure the camera's calibration, part by part (docs/calibration.md)");
  calibrate->require_subcommand(1);
  addCalibrateDarkCommand(*calibrate, action);
  addCalibrateFlatCommand(*calibrate, action);
  addCalibrateLinearityCommand(*calibrate, action);
  addCalibrateNoiseCommand(*calibrate, action);
  addCalibrateLuminanceCommand(*calibrate, action);
  addCalibrateIntrinsicsCommand(*calibrate, action);
  addCalibrateMergeCommand(*calibrate, action);
}

}  // namespace glarecam::apps
