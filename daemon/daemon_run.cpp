#include "daemon/daemon_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>

#include "daemon/signal_forwarder.h"
#include "daemon/status/log_ring.h"
#include "daemon/status/status_server.h"

namespace glarecam::daemon {

Result<DaemonRig> prepareDaemonRig(const DaemonRunOptions& run) {
  GLARECAM_CHECK(run.validate());
  DaemonRig rig;
  rig.options.output_root = run.output_root;
  rig.options.interval = run.interval;
  rig.options.max_stacks = run.max_stacks;
  rig.options.status_listen = run.status_listen;
  if (run.max_use_gib)
    rig.options.max_use_bytes = static_cast<std::uint64_t>(*run.max_use_gib * kBytesPerGib);
  if (run.reserve_mb) rig.options.reserve_bytes = static_cast<std::uint64_t>(*run.reserve_mb) << 20;
  if (!run.simulate) {
    if (run.config_path) rig.options.config_path = *run.config_path;
    rig.clock = std::make_unique<SystemDaemonClock>();
    return rig;
  }
  const UtcTime start = run.simulation_start.value_or(defaultSimulationStart(!run.interval));
  const SimulatedRigOptions simulated{.output = *run.output_root,
                                      .camera = run.simulated_camera.value_or("sim:seed=1"),
                                      .interval = run.interval};
  GLARECAM_ASSIGN(rig.options.config_path, writeSimulatedRigConfig(simulated));
  rig.clock = std::make_unique<TimeLapseClock>(start, run.time_lapse);
  spdlog::info("glarecamd: simulated rig {}; the sun from {} at {:g}× real time",
               rig.options.config_path.string(), formatIsoTime(start), run.time_lapse);
  return rig;
}

namespace {

// The status page, when the config asks for one. One that cannot listen is an error in the log
// and on no page, not a reason to stop measuring.
std::unique_ptr<StatusServer> startStatusPage(const Config& config, const StatusBoard& board,
                                              const DaemonClock& clock) {
  const auto& listen = config.daemon.status.listen;
  if (!listen) return nullptr;
  // The page's log: a sink beside the journal's, added while this is the only thread. On a
  // simulated clock each entry carries its time too.
  auto log = std::make_shared<LogRing>(kStatusLogEntries, clock.simulated() ? &clock : nullptr);
  spdlog::default_logger()->sinks().push_back(log);
  auto server = StatusServer::start(*listen, board, std::move(log));
  if (!server) {
    spdlog::error("glarecamd: {}; glarecamd runs without it", server.error().message);
    return nullptr;
  }
  spdlog::info("glarecamd: status page at {}", (*server)->url());
  return std::move(*server);
}

}  // namespace

Status DaemonRunOptions::validate() const {
  if (max_use_gib && !(*max_use_gib >= kMinMaxUseGib && *max_use_gib <= kMaxMaxUseGib))
    return badInput(
        fmt::format("--max-use-gib must be between {:g} and {:g}", kMinMaxUseGib, kMaxMaxUseGib));
  if (reserve_mb && !(*reserve_mb >= 0 && *reserve_mb <= kMaxReserveMb))
    return badInput(fmt::format("--reserve-mb must be between 0 and {}", kMaxReserveMb));
  if (simulate && config_path)
    return badInput("--simulate runs the simulated rig: give --config or --simulate, not both");
  if (simulate && !output_root) return badInput("--simulate needs --output DIR");
  if (!simulate && (simulated_camera || simulation_start))
    return badInput("--camera and --start are options of --simulate");
  if (output_root && output_root->empty()) return badInput("--output: expected a directory");
  if (interval && !(interval->count() >= 1 && *interval <= kMaxDaemonInterval))
    return badInput("--interval must be between 1 and 604800 seconds (a week)");
  if (max_stacks && *max_stacks == 0) return badInput("--count must be at least 1");
  if (!(time_lapse >= 1 && time_lapse <= kMaxTimeLapse))
    return badInput("--time-lapse must be between 1 and 100000");
  return {};
}

Status runDaemon(const DaemonRig& rig) {
  const auto notifier = makeSystemdNotifier();
  const auto disk = makeStatvfsDiskProbe();
  StatusBoard board;
  std::unique_ptr<CaptureDaemon> daemon;
  GLARECAM_ASSIGN(daemon, CaptureDaemon::create(rig.options, {.clock = rig.clock.get(),
                                                              .notifier = notifier.get(),
                                                              .disk = disk.get(),
                                                              .status_board = &board}));
  const std::unique_ptr<StatusServer> page = startStatusPage(daemon->config(), board, *rig.clock);
  const SignalForwarder signals(daemon->events());
  return daemon->run();
}

}  // namespace glarecam::daemon
