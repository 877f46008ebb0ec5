#include "apps/glarecam/cli.h"

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <iostream>
#include <string>

#include "apps/common/parse_error.h"
#include "apps/common/value_types.h"
#include "apps/glarecam/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "core/logging.h"
#include "core/version.h"

namespace glarecam::apps {

namespace {

// "glarecam inclinometer read": the command line's chosen (sub)commands, for the help hint.
std::string commandPath(const CLI::App& app) {
  std::string path = "glarecam";
  for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
    sub = sub->get_subcommands().front();
    path += " " + sub->get_name();
  }
  return path;
}

// Runs the chosen command; a library exception (out of memory, a bug) becomes a one-line
// error and exit status 1 instead of an abort.
Status runAction(const std::function<Status()>& action) {
  if (!action) return badInput("no command given");
  return catchExceptions(action);
}

}  // namespace

void printJson(const nlohmann::json& document) { std::fputs(jsonText(document).c_str(), stdout); }

int runGlarecam(int argc, char** argv) {
  CLI::App app{
      "glarecam: measures glare of PV modules from bracketed camera stacks.\n"
      "Docs: docs/process.md, docs/sweep.md, docs/datasheet.md, docs/glare-profile.md,\n"
      "docs/cameras.md, docs/calibration.md, docs/rig.md, docs/illuminance.md, docs/operator.md,\n"
      "docs/simulate.md, docs/hazard.md, docs/hazard-report.md, docs/ocular-hazard.md,\n"
      "docs/weather-files.md, docs/brdf.md, docs/cluster.md, docs/stack-format.md,\n"
      "docs/method.md"};
  app.set_version_flag("--version", kVersion);
  // `--json=yes` is refused, not read as true: a flag takes no value (subcommands inherit this).
  app.option_defaults()->disable_flag_override();
  app.require_subcommand(1);
  app.fallthrough();  // global options (-v, -q) also after the subcommand
  bool verbose = false, quiet = false, debug = false;
  app.add_flag("-v,--verbose", verbose, "log progress details");
  app.add_flag("--debug", debug, "log everything");
  app.add_flag("-q,--quiet", quiet, "log errors only");

  std::function<Status()> action;
  addSimulateCommand(app, action);
  addSimulateCalibrationCommand(app, action);
  addProcessCommand(app, action);
  addSweepCommand(app, action);
  addFitCommand(app, action);
  addDatasheetCommand(app, action);
  addModelCommand(app, action);
  addCamerasCommand(app, action);
  addCaptureCommand(app, action);
  addFakeCameraCommand(app, action);
  addSunCommand(app, action);
  addAlphaCommand(app, action);
  addInclinometerCommand(app, action);
  addGpioCommand(app, action);
  addDoctorCommand(app, action);
  addCalibrateCommand(app, action);
  addHazardCommand(app, action);
  addBrdfCommand(app, action);
  addSimulateBrdfCommand(app, action);
  addRouteCheckCommand(app, action);
  nameOptionValues(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "glarecam: %s (see %s --help)\n",
                 parseErrorMessage(app, e, argc, argv).c_str(), commandPath(app).c_str());
    return kExitBadInput;
  }
  initLogging(debug     ? Verbosity::kDebug
              : verbose ? Verbosity::kVerbose
              : quiet   ? Verbosity::kQuiet
                        : Verbosity::kNormal);
  Status status = runAction(action);
  if (!status) {
    std::fprintf(stderr, "glarecam: %s\n", status.error().message.c_str());
    return exitStatus(status.error());
  }
  return kExitSuccess;
}

}  // namespace glarecam::apps
