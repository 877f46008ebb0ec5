#include "apps/glarecamd/daemon_cli.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/common/parse_error.h"
#include "apps/common/value_types.h"
#include "core/logging.h"
#include "core/time.h"
#include "core/version.h"
#include "daemon/daemon_run.h"
#include "daemon/journal_sink.h"
#include "daemon/signal_forwarder.h"

namespace glarecam::apps {

namespace {

struct DaemonArgs {
  std::optional<std::string> config, output, camera, start, status;
  std::optional<std::int64_t> interval_s, reserve_mb;
  std::optional<double> max_use_gib;
  std::optional<std::uint64_t> count;
  bool simulate = false;
  double time_lapse = daemon::kDefaultTimeLapse;
  std::string log_target = "auto";
  bool verbose = false, quiet = false, debug = false;
};

void addOptions(CLI::App& app, DaemonArgs& args) {
  app.set_version_flag("--version", kVersion);
  app.add_option("--config", args.config,
                 "rig config (TOML, docs/operator.md; default /etc/glarecam/glarecam.toml)");
  app.add_option("--output", args.output, "output root: overrides the config's [output] root");
  app.add_option("--interval", args.interval_s,
                 "capture every S seconds: overrides the config's [schedule]");
  app.add_option("--max-use-gib", args.max_use_gib,
                 "retention by space alone: keep the output tree within G GiB, the least valuable "
                 "of past days first (overrides the config's [output] retention; keep_*_days are "
                 "not applied; docs/operator.md \"Retention\")")
      ->type_name("G");
  app.add_option("--reserve-mb", args.reserve_mb,
                 "pause capture below M MiB free: overrides the config's [output] reserve_mb")
      ->type_name("M");
  app.add_option("--count", args.count, "stop after N stacks are done (for demos and tests)");
  app.add_option("--status", args.status,
                 "serve the read-only status page on ADDRESS:PORT (e.g. 127.0.0.1:8080, "
                 "[::1]:8080; port 0 takes a free one, logged): overrides the config's [status] "
                 "listen; docs/operator.md")
      ->type_name("ADDR:PORT");
  app.add_flag("--simulate", args.simulate,
               "run against the simulated rig (sim: camera, inclinometer and GPIO; a time-lapse "
               "sun sweeping α); needs --output");
  app.add_option("--camera", args.camera,
                 "with --simulate: the sim: camera URI (docs/simulate.md)");
  app.add_option("--time-lapse", args.time_lapse,
                 "with --simulate: simulated seconds per real second")
      ->capture_default_str();
  app.add_option("--start", args.start,
                 "with --simulate: the simulated clock's start, ISO 8601 with a zone (default "
                 "2026-06-21T05:25:00Z, with --interval 06:30:00Z)");
  app.add_option("--log-target", args.log_target,
                 "auto (the journal when systemd connected stderr to it), journal or console")
      ->capture_default_str();
  app.add_flag("-v,--verbose", args.verbose, "log debug details");
  app.add_flag("--debug", args.debug, "log everything");
  app.add_flag("-q,--quiet", args.quiet, "log warnings and errors only");
}

Result<daemon::DaemonRunOptions> runOptions(const DaemonArgs& args) {
  if (args.log_target != "auto" && args.log_target != "journal" && args.log_target != "console")
    return badInput("--log-target must be auto, journal or console");
  daemon::DaemonRunOptions run;
  if (args.config) run.config_path = *args.config;
  if (args.output) run.output_root = *args.output;
  if (args.interval_s) {
    if (!(*args.interval_s >= 1 && *args.interval_s <= daemon::kMaxDaemonInterval.count()))
      return badInput("--interval must be between 1 and 604800 seconds (a week)");
    run.interval = std::chrono::seconds(*args.interval_s);
  }
  run.max_stacks = args.count;
  run.max_use_gib = args.max_use_gib;
  run.reserve_mb = args.reserve_mb;
  if (args.status) {
    auto listen = daemon::parseListenAddress(*args.status);
    if (!listen) return badInput("--status: " + listen.error().message);
    run.status_listen = std::move(*listen);
  }
  run.simulate = args.simulate;
  run.simulated_camera = args.camera;
  if (args.start) {
    if (!args.simulate) return badInput("--camera and --start are options of --simulate");
    GLARECAM_ASSIGN(run.simulation_start, parseIsoTime(*args.start));
  }
  run.time_lapse = args.time_lapse;
  GLARECAM_CHECK(run.validate());
  return run;
}

void setUpLogging(const DaemonArgs& args) {
  // A daemon's log says what it does: info unless asked otherwise.
  const Verbosity verbosity = args.debug     ? Verbosity::kDebug
                              : args.verbose ? Verbosity::kDebug
                              : args.quiet   ? Verbosity::kNormal
                                             : Verbosity::kVerbose;
  const bool journal =
      args.log_target == "journal" || (args.log_target == "auto" && daemon::stderrIsJournal());
  if (journal)
    initLogging(verbosity, daemon::makeJournalSink("glarecamd"));
  else
    initLogging(verbosity);
}

}  // namespace

int runGlarecamd(int argc, char** argv) {
  daemon::blockDaemonSignals();  // before any thread starts: every thread inherits the mask
  CLI::App app{
      "glarecamd: the rig's capture daemon. Captures bracketed stacks on schedule, processes\n"
      "each one, keeps each day's sweep table and data sheet current, and reports to systemd.\n"
      "Signals: SIGTERM stops, SIGHUP reloads the config, SIGUSR1 takes a stack now.\n"
      "Docs: docs/operator.md"};
  app.option_defaults()->disable_flag_override();  // `--simulate=yes` is refused
  DaemonArgs args;
  addOptions(app, args);
  nameOptionValues(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "glarecamd: %s (see glarecamd --help)\n",
                 parseErrorMessage(app, e, argc, argv).c_str());
    return kExitBadInput;
  }
  const Result<daemon::DaemonRunOptions> run = runOptions(args);
  if (!run) {
    std::fprintf(stderr, "glarecamd: %s (see glarecamd --help)\n", run.error().message.c_str());
    return kExitBadInput;
  }
  setUpLogging(args);
  const Result<daemon::DaemonRig> rig =
      catchExceptions([&] { return daemon::prepareDaemonRig(*run); });
  if (!rig) {
    spdlog::critical("glarecamd: {}", rig.error().message);
    return rig.error().code == ErrorCode::kBadInput ? kExitBadInput : kExitFailure;
  }
  const Status ran = catchExceptions([&] { return daemon::runDaemon(*rig); });
  if (ran) return kExitSuccess;
  spdlog::critical("glarecamd: {}", ran.error().message);
  return ran.error().code == ErrorCode::kBadInput ? kExitConfig : kExitFailure;
}

}  // namespace glarecam::apps
