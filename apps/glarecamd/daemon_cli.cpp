#include "apps/glarecamd/daemon_cli.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "core/logging.h"
#include "core/version.h"
#include "daemon/capture_daemon.h"
#include "daemon/journal_sink.h"
#include "daemon/signal_forwarder.h"
#include "daemon/simulated_rig.h"

namespace glarecam::apps {

namespace {

constexpr std::int64_t kMaxIntervalS = 7 * 86400;  // a week, as [schedule] interval_s
constexpr double kMaxTimeLapse = 1e5;              // a day in under a second

struct DaemonArgs {
  std::optional<std::string> config, output, camera, start;
  std::optional<std::int64_t> interval_s;
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
  app.add_option("--count", args.count, "stop after N stacks are done (for demos and tests)");
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

Status checkArgs(const DaemonArgs& args) {
  if (args.simulate && args.config)
    return badInput("--simulate runs the simulated rig: give --config or --simulate, not both");
  if (args.simulate && !args.output) return badInput("--simulate needs --output DIR");
  if (!args.simulate && (args.camera || args.start))
    return badInput("--camera and --start are options of --simulate");
  if (args.output && args.output->empty()) return badInput("--output: expected a directory");
  if (args.interval_s && !(*args.interval_s >= 1 && *args.interval_s <= kMaxIntervalS))
    return badInput("--interval must be between 1 and 604800 seconds (a week)");
  if (args.count && *args.count == 0) return badInput("--count must be at least 1");
  if (!(args.time_lapse >= 1 && args.time_lapse <= kMaxTimeLapse))
    return badInput("--time-lapse must be between 1 and 100000");
  if (args.log_target != "auto" && args.log_target != "journal" && args.log_target != "console")
    return badInput("--log-target must be auto, journal or console");
  return {};
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

struct Rig {
  daemon::DaemonOptions options;
  std::unique_ptr<daemon::DaemonClock> clock;
};

Result<Rig> rigFor(const DaemonArgs& args) {
  Rig rig;
  if (args.output) rig.options.output_root = *args.output;
  if (args.interval_s) rig.options.interval = std::chrono::seconds(*args.interval_s);
  rig.options.max_stacks = args.count;
  if (!args.simulate) {
    if (args.config) rig.options.config_path = *args.config;
    rig.clock = std::make_unique<daemon::SystemDaemonClock>();
    return rig;
  }
  UtcTime start = daemon::defaultSimulationStart(!rig.options.interval);
  if (args.start) GLARECAM_ASSIGN(start, sun::parseIsoTime(*args.start));
  daemon::SimulatedRigOptions simulated{.output = *args.output,
                                        .camera = args.camera.value_or("sim:seed=1"),
                                        .interval = rig.options.interval};
  GLARECAM_ASSIGN(rig.options.config_path, daemon::writeSimulatedRigConfig(simulated));
  rig.clock = std::make_unique<daemon::TimeLapseClock>(start, args.time_lapse);
  spdlog::info("glarecamd: simulated rig {}; the sun from {} at {:g}× real time",
               rig.options.config_path.string(), sun::formatIsoTime(start), args.time_lapse);
  return rig;
}

// Runs the daemon until it stops; its errors: a config problem (kBadInput) or a failure.
Status runDaemon(Rig& rig) {
  const auto notifier = daemon::makeSystemdNotifier();
  const auto disk = daemon::makeStatvfsDiskProbe();
  std::unique_ptr<daemon::CaptureDaemon> daemon;
  GLARECAM_ASSIGN(daemon, daemon::CaptureDaemon::create(rig.options, {.clock = rig.clock.get(),
                                                                      .notifier = notifier.get(),
                                                                      .disk = disk.get()}));
  const daemon::SignalForwarder signals(daemon->events());
  return daemon->run();
}

int reportFailure(const Error& error, int status) {
  spdlog::critical("glarecamd: {}", error.message);
  return status;
}

}  // namespace

int runGlarecamd(int argc, char** argv) {
  daemon::blockDaemonSignals();  // before any thread starts: every thread inherits the mask
  CLI::App app{
      "glarecamd: the rig's capture daemon. Captures bracketed stacks on schedule, processes\n"
      "each one, keeps each day's sweep table and data sheet current, and reports to systemd.\n"
      "Signals: SIGTERM stops, SIGHUP reloads the config, SIGUSR1 takes a stack now.\n"
      "Docs: docs/operator.md"};
  DaemonArgs args;
  addOptions(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "glarecamd: %s (see glarecamd --help)\n", e.what());
    return kExitBadInput;
  }
  if (const Status checked = checkArgs(args); !checked) {
    std::fprintf(stderr, "glarecamd: %s (see glarecamd --help)\n", checked.error().message.c_str());
    return kExitBadInput;
  }
  setUpLogging(args);
  Result<Rig> rig = catchExceptions([&] { return rigFor(args); });
  if (!rig)
    return reportFailure(rig.error(),
                         rig.error().code == ErrorCode::kBadInput ? kExitBadInput : kExitFailure);
  const Status ran = catchExceptions([&] { return runDaemon(*rig); });
  if (!ran)
    return reportFailure(ran.error(),
                         ran.error().code == ErrorCode::kBadInput ? kExitConfig : kExitFailure);
  return kExitSuccess;
}

}  // namespace glarecam::apps
