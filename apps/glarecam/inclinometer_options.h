// The options `glarecam inclinometer read` and `flip` share: which sensor (--inclinometer, else
// the --config's), its tilt options and the calibration file holding the zero offset.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "rig/inclinometer/tilt.h"

namespace glarecam::apps {

struct InclinometerArgs {
  std::optional<std::string> uri, config, calibration, out;
  std::optional<std::string> samples;
  std::vector<std::string> from;
  bool json = false;
  bool no_progress = false;
};

// The sensor to use: --inclinometer, else the config's; with the config's tilt options.
struct InclinometerChoice {
  std::string uri;
  rig::TiltOptions tilt;
  std::optional<std::filesystem::path> calibration;  // --calibration, else the config's
};

// kBadInput naming `command` when no sensor is named, or the tilt options are out of range.
Result<InclinometerChoice> chooseInclinometer(const InclinometerArgs& args, const char* command);

void addInclinometerSource(CLI::App* sub, InclinometerArgs& args);

}  // namespace glarecam::apps
