// glarecam inclinometer flip: the inclinometer's zero offset by the flip method, taken now or
// from two saved readings (rig/inclinometer/flip_calibration.h; docs/rig.md).
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/inclinometer_options.h"
#include "daemon/daemon_config.h"
#include "rig/inclinometer/flip_calibration.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/zero_offset_file.h"

namespace glarecam::apps {
namespace {

// The file the offset goes into (--calibration, else the config's), and the configured sensor.
Result<std::filesystem::path> flipCalibrationFile(const InclinometerArgs& args,
                                                  InclinometerChoice& choice) {
  if (args.from.empty()) {
    GLARECAM_ASSIGN(choice, chooseInclinometer(args, "flip"));
  } else if (args.calibration) {
    choice.calibration = *args.calibration;
  } else if (args.config) {
    rig::RigConfig config;
    GLARECAM_ASSIGN(config, daemon::readRigConfig(*args.config));
    choice.calibration = config.calibration;
    if (config.inclinometer) choice.uri = config.inclinometer->uri;
  }
  if (!args.from.empty() && args.uri) choice.uri = *args.uri;  // the sensor the readings are of
  if (!choice.calibration)
    return badInput(
        "inclinometer flip: give --calibration FILE (or a --config naming one) to "
        "store the zero offset in");
  // Before anybody turns a sensor: the file must be one the offset can be written into.
  GLARECAM_CHECK(rig::checkZeroOffsetWritable(*choice.calibration));
  return *choice.calibration;
}

// Between the live readings: the operator turns the frame and presses Enter.
Status askForTheTurn(const rig::TiltReading& first) {
  std::fprintf(stderr,
               "First reading: tilt x %.4f°, y %.4f°.\nTurn the frame with the sensor 180° on the "
               "surface, into the same outline; let it settle, then press Enter.\n",
               first.raw_tilt.x_deg, first.raw_tilt.y_deg);
  std::string line;
  if (!std::getline(std::cin, line))
    return badInput(
        "inclinometer flip: stdin closed before the second reading (to compute from "
        "saved readings: --from FIRST.json SECOND.json)");
  return {};
}

Result<rig::FlipReadings> flipReadings(const InclinometerArgs& args,
                                       const InclinometerChoice& choice) {
  if (!args.from.empty()) return rig::savedFlipReadings(args.from[0], args.from[1]);
  std::unique_ptr<rig::Inclinometer> sensor;
  GLARECAM_ASSIGN(sensor, rig::openInclinometer(choice.uri));
  return rig::takeFlipReadings(*sensor, choice.uri, choice.tilt, askForTheTurn, !args.no_progress);
}

Status runInclinometerFlip(const InclinometerArgs& args) {
  InclinometerChoice choice;
  std::filesystem::path calibration;
  GLARECAM_ASSIGN(calibration, flipCalibrationFile(args, choice));
  rig::FlipReadings readings;
  GLARECAM_ASSIGN(readings, flipReadings(args, choice));
  rig::FlipCalibration flip;
  GLARECAM_ASSIGN(flip, rig::storeFlipCalibration(calibration, readings, choice.uri));
  const rig::TiltReading& first = readings.first.reading;
  const rig::TiltReading& second = readings.second.reading;
  std::printf(
      "readings: tilt x %.4f°, y %.4f° and x %.4f°, y %.4f°; surface tilt x %.4f°, y %.4f°\n"
      "zero offset x %.4f°, y %.4f° (± %.2g°) written to %s\n",
      first.raw_tilt.x_deg, first.raw_tilt.y_deg, second.raw_tilt.x_deg, second.raw_tilt.y_deg,
      flip.surface_x_deg, flip.surface_y_deg, flip.zero.offset.x_deg, flip.zero.offset.y_deg,
      flip.zero.uncertainty_deg, calibration.c_str());
  return {};
}

}  // namespace

void addInclinometerFlipCommand(CLI::App& inclinometer, Action& action) {
  auto args = std::make_shared<InclinometerArgs>();
  CLI::App* flip = inclinometer.add_subcommand(
      "flip",
      "Zero-offset calibration by the flip method: a reading, then you turn the frame 180° "
      "on the surface and press Enter, a second reading; stores the offset in the "
      "calibration file (docs/rig.md)");
  addInclinometerSource(flip, *args);
  flip->add_option("--from", args->from,
                   "compute from two saved readings (inclinometer read --out) instead")
      ->expected(2);
  flip->callback([args, &action] { action = [args] { return runInclinometerFlip(*args); }; });
}

}  // namespace glarecam::apps
