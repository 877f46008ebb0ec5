// glarecam inclinometer read: a tilt reading with the stored zero offset removed
// (rig/inclinometer/tilt.h; docs/rig.md); the options both inclinometer commands share.
#include <fmt/format.h>

#include <climits>
#include <cstdio>
#include <memory>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/inclinometer_options.h"
#include "apps/glarecam/option_parsing.h"
#include "core/atomic_file.h"
#include "core/json.h"
#include "core/time.h"
#include "daemon/daemon_config.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/sample_progress.h"
#include "rig/inclinometer/zero_offset_file.h"

namespace glarecam::apps {

Result<InclinometerChoice> chooseInclinometer(const InclinometerArgs& args, const char* command) {
  InclinometerChoice choice;
  if (args.config) {
    rig::RigConfig config;
    GLARECAM_ASSIGN(config, daemon::readRigConfig(*args.config));
    if (config.inclinometer) {
      choice.uri = config.inclinometer->uri;
      choice.tilt = config.inclinometer->tilt;
    }
    choice.calibration = config.calibration;
  }
  if (args.uri) choice.uri = *args.uri;
  if (args.calibration) choice.calibration = *args.calibration;
  if (choice.uri.empty())
    return badInput(
        fmt::format("inclinometer {}: give --inclinometer URI, or --config with an "
                    "[inclinometer] uri",
                    command));
  if (args.samples) {
    std::uint64_t samples = 0;
    GLARECAM_ASSIGN(samples, parseUnsigned(*args.samples, "--samples"));
    choice.tilt.samples = static_cast<int>(std::min<std::uint64_t>(samples, INT_MAX));
  }
  GLARECAM_CHECK(choice.tilt.validate());  // the range, as for the config's
  return choice;
}

void addInclinometerSource(CLI::App* sub, InclinometerArgs& args) {
  sub->add_option("--inclinometer", args.uri,
                  "inclinometer URI: adxl355:/dev/i2c-1@0x1d, iio:iio:device0, or the simulator "
                  "sim:TILT_DEG[,roll_deg=,offset_x_deg=,offset_y_deg=,noise_g=,seed=,"
                  "temperature_c=,fault=] (docs/rig.md)");
  sub->add_option("--config", args.config, "rig config (TOML) naming the inclinometer");
  sub->add_option("--calibration", args.calibration,
                  "calibration file holding the zero offset (default: the config's)");
  sub->add_option("--samples", args.samples, "samples averaged per reading (default 50)");
  sub->add_flag("--no-progress", args.no_progress, "no progress on stderr");
}

namespace {

void printReading(const rig::TiltReading& r) {
  std::printf("tilt x %.4f°, y %.4f°; module tilt %.4f° ± %.2g° (σ %.2g° over %d samples",
              r.tilt.x_deg, r.tilt.y_deg, r.module_tilt_deg, r.tilt_uncertainty_deg, r.tilt_std_deg,
              r.samples);
  if (r.mean.temperature_c) std::printf(", %.1f °C", *r.mean.temperature_c);
  std::printf(")\n");
}

Status runInclinometerRead(const InclinometerArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  InclinometerChoice choice;
  GLARECAM_ASSIGN(choice, chooseInclinometer(args, "read"));
  std::optional<rig::InclinometerZeroOffset> stored;
  std::error_code ec;
  if (choice.calibration && std::filesystem::exists(*choice.calibration, ec))
    GLARECAM_ASSIGN(stored, rig::readZeroOffset(*choice.calibration));
  const rig::InclinometerZeroOffset zero = stored.value_or(rig::InclinometerZeroOffset{});
  std::unique_ptr<rig::Inclinometer> sensor;
  GLARECAM_ASSIGN(sensor, rig::openInclinometer(choice.uri));
  rig::TiltReading reading;
  GLARECAM_ASSIGN(reading, rig::withSampleProgress(choice.tilt.samples, !args.no_progress,
                                                   [&](const std::function<void()>& on_sample) {
                                                     return rig::measureTilt(*sensor, choice.tilt,
                                                                             zero, on_sample);
                                                   }));
  nlohmann::json document = rig::tiltReadingJson(reading);
  document["uri"] = choice.uri;
  document["time"] = formatIsoTime(utcNow());
  document["zero_offset_applied"] = stored.has_value();
  if (args.out) GLARECAM_CHECK(writeFileAtomic(*args.out, jsonText(document)));
  if (args.json) {
    printJson(document);
  } else {
    printReading(reading);
    if (stored)
      std::printf("zero offset x %.4f°, y %.4f° removed (from %s)\n", zero.offset.x_deg,
                  zero.offset.y_deg, choice.calibration->c_str());
    else
      std::printf("no zero offset removed (none stored: glarecam inclinometer flip)\n");
  }
  return {};
}

}  // namespace

void addInclinometerCommand(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "inclinometer", "Read the inclinometer, or calibrate its zero offset (docs/rig.md)");
  sub->require_subcommand(1);
  auto read_args = std::make_shared<InclinometerArgs>();
  CLI::App* read = sub->add_subcommand(
      "read", "Average a tilt reading (the stored zero offset removed) and print it");
  addInclinometerSource(read, *read_args);
  read->add_flag("--json", read_args->json, "print the reading as JSON");
  read->add_option("--out", read_args->out, "also write the reading (JSON) to this file");
  read->callback(
      [read_args, &action] { action = [read_args] { return runInclinometerRead(*read_args); }; });
  addInclinometerFlipCommand(*sub, action);
}

}  // namespace glarecam::apps
