// Subcommands of the glarecam CLI. Each add*Command registers its options on `app` and, when
// its subcommand is chosen, sets `action` to the work to run after parsing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace glarecam::apps {

using Action = std::function<Status()>;

void addSimulateCommand(CLI::App& app, Action& action);
void addProcessCommand(CLI::App& app, Action& action);
void addSweepCommand(CLI::App& app, Action& action);
void addFitCommand(CLI::App& app, Action& action);
void addDatasheetCommand(CLI::App& app, Action& action);
void addModelCommand(CLI::App& app, Action& action);
void addCamerasCommand(CLI::App& app, Action& action);
void addCaptureCommand(CLI::App& app, Action& action);
void addFakeCameraCommand(CLI::App& app, Action& action);
void addSunCommand(CLI::App& app, Action& action);
void addAlphaCommand(CLI::App& app, Action& action);
void addInclinometerCommand(CLI::App& app, Action& action);
// `inclinometer flip`, under the inclinometer command.
void addInclinometerFlipCommand(CLI::App& inclinometer, Action& action);
void addGpioCommand(CLI::App& app, Action& action);
void addDoctorCommand(CLI::App& app, Action& action);
void addCalibrateCommand(CLI::App& app, Action& action);
void addSimulateCalibrationCommand(CLI::App& app, Action& action);
void addHazardCommand(CLI::App& app, Action& action);
void addBrdfCommand(CLI::App& app, Action& action);
void addSimulateBrdfCommand(CLI::App& app, Action& action);
void addRouteCheckCommand(CLI::App& app, Action& action);

// A JSON document on stdout, as every --json prints it.
void printJson(const nlohmann::json& document);

}  // namespace glarecam::apps
