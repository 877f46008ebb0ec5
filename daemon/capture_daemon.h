// glarecamd's core: the only long-lived owner of the rig's hardware. One event loop (one thread)
// captures on schedule (capture_schedule.h: a fixed interval, the α targets as the sun moves; and
// the operator's button, SIGUSR1), hands each bracket to the stack worker (stack_worker.h: written
// atomically, processed, the day's data sheet updated) and survives what a field throws at it:
//
//   camera lost       the stack is discarded, the camera reopened with capped exponential
//                     backoff (camera_supervisor.h); after camera_max_failures in a row run()
//                     fails (kHardware) and systemd restarts the daemon
//   inclinometer      a failed read or an implausible tilt (rig_session.h): the stack is taken
//                     with α unknown, or capture pauses, per [faults] inclinometer
//   illuminance       the instrument sampled during each bracket fails, or its reading is
//                     refused (illuminance_session.h): the stack is taken unreferred, a warning
//   disk              below the reserve or read-only (health_monitor.h): capture pauses, resumes
//                     when space returns; a stack whose write failed is kept and written later
//   clock             not synchronised: said in STATUS, and every stack flagged
//
// systemd (service_notifier.h): READY=1 once the camera is open, STATUS= whenever the status
// line changes, WATCHDOG=1 from the loop itself (health_monitor.h) and before a bracket in which
// one would fall due (bracket_watchdog.h), STOPPING=1 on SIGTERM, after which queued stacks are
// written and run() returns. SIGHUP reloads the config (a bad one is reported and the old one
// kept).
//
// The daemon owns the loop (run, step, handle) and one capture: it schedules and dispatches. The
// schedule, the rig session, the health checks, the watchdog's bracket estimate
// (bracket_watchdog.h), what an inclinometer fault means for capture (inclinometer_faults.h), when
// retention runs (retention_scheduler.h), what a restart recalls of the run before it
// (earlier_run.h) and the output tree are each their own class. Everything it
// touches is injected (DaemonServices): tests run it on a manual clock with a scripted camera,
// disk and notifier, one thread, no sleeping.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "core/error.h"
#include "daemon/bracket_watchdog.h"
#include "daemon/capture_schedule.h"
#include "daemon/daemon_clock.h"
#include "daemon/daemon_config.h"
#include "daemon/daemon_events.h"
#include "daemon/hardware/camera_supervisor.h"
#include "daemon/hardware/illuminance_session.h"
#include "daemon/hardware/inclinometer_faults.h"
#include "daemon/hardware/rig_session.h"
#include "daemon/health_monitor.h"
#include "daemon/service_notifier.h"
#include "daemon/stack_worker.h"
#include "daemon/status/daemon_status.h"
#include "daemon/status/status_board.h"
#include "daemon/storage/disk_space.h"
#include "daemon/storage/output_tree.h"
#include "daemon/storage/retention_scheduler.h"

namespace glarecam::daemon {

struct DaemonServices {
  DaemonClock* clock = nullptr;
  ServiceNotifier* notifier = nullptr;
  DiskProbe* disk = nullptr;
  CameraOpener open_camera{};  // default capture::openCamera
  RigIoOpener open_rig_io{};   // default rig::openRigIo
  StackWorker::Mode worker_mode = StackWorker::Mode::kThread;
  bool watch_button = true;  // a thread polls the button (tests post ButtonEvents instead)
  std::function<void()> worker_job_hook{};  // tests: runs at the start of every worker job
  StatusBoard* status_board = nullptr;      // the status page's: a snapshot every step
};

struct DaemonOptions {
  std::filesystem::path config_path = rig::kDefaultRigConfigPath;
  std::optional<std::filesystem::path> output_root{};  // overrides [output] root
  std::optional<std::chrono::seconds> interval{};      // overrides [schedule]: a fixed interval
  std::optional<std::uint64_t> max_stacks{};  // stop once this many stacks are done (tests, demos)
  std::optional<ListenAddress> status_listen{};  // overrides [status] listen
  // Override [output]: retention by space alone within this budget (keep_*_days not applied),
  // and the reserve.
  std::optional<std::uint64_t> max_use_bytes{};
  std::optional<std::uint64_t> reserve_bytes{};
};

// The config with the command line's overrides applied: the one place they are.
Config effectiveConfig(Config config, const DaemonOptions& options);

// What asked for a stack: the schedule, the operator's button or SIGUSR1.
enum class CaptureTrigger { kSchedule, kButton, kSignal };

class CaptureDaemon {
 public:
  // Reads the config: kBadInput "FILE:LINE: problem" when it is invalid (glarecamd exits 78).
  static Result<std::unique_ptr<CaptureDaemon>> create(DaemonOptions options,
                                                       DaemonServices services);
  ~CaptureDaemon();
  CaptureDaemon(const CaptureDaemon&) = delete;
  CaptureDaemon& operator=(const CaptureDaemon&) = delete;

  // Runs until SIGTERM or SIGINT, or max_stacks. kBadInput when the config's camera cannot be
  // opened as configured; kHardware when it failed camera_max_failures times in a row.
  Status run();

  // Signals, button presses and the worker's reports arrive here (from any thread).
  EventQueue& events() { return events_; }
  const DaemonState& state() const { return state_; }
  const Config& config() const { return config_; }

 private:
  CaptureDaemon(DaemonOptions options, DaemonServices services, Config config);

  // The loop.
  Status start();
  Status step();
  void stop();
  void handle(const DaemonEvent& event);
  void handleWorker(const WorkerEvent& event);
  // Ready, a camera open, not stopping and --count not reached: a due capture is taken now.
  bool mayCapture() const;
  SteadyTime nextDeadline(SteadyTime now) const;

  // The config and what it opens.
  Status checkConfig(const Config& config) const;
  Status checkReloadedCamera(const Config& config);
  void applyConfig();
  void reload();
  void openGpio();
  void closeGpio();
  void prepareOutput(bool clean);
  Status reopenCamera(SteadyTime now);
  Status cameraFailed(const Error& error, SteadyTime now, bool mid_bracket);

  // One capture: the stack, then (a scheduled one) the next slot planned.
  Status capture(CaptureTrigger trigger);
  // The stack itself, or why not (`target_deg`: the scheduled slot's α target).
  Status takeStack(CaptureTrigger trigger, const StackTimeline& timeline,
                   std::optional<double> target_deg);
  void finishStack(capture::CapturedStack& stack, const std::optional<rig::RigGeometry>& geometry,
                   CaptureTrigger trigger, UtcTime bracket_start, UtcTime bracket_end);

  // The schedule and the checks.
  // `slot_taken`: the start of the scheduled stack just done (CaptureSchedule::plan).
  void planNext(std::optional<UtcTime> slot_taken);
  void checkWallClock();
  void checkDisk();
  void checkClock();
  // Warns once when max_use_gib cannot hold one day's stacks (day_budget.h): at start, or after
  // the run's first stack when the output held none to measure.
  void checkDayBudget();
  // The rig's clock's state (rigClockStatus): the status, /metrics and the stacks' flags.
  sun::ClockStatus clockStatus() const;
  // The running worker job's start, for the watchdog (none: idle, or no worker yet).
  std::optional<SteadyTime> workerBusySince() const;
  void publishStatus();
  StatusSnapshot snapshot() const;
  std::optional<double> siteLongitude() const;  // [site] longitude: days are its solar days

  DaemonOptions options_;
  DaemonServices services_;
  Config config_;
  DaemonClock& clock_;
  EventQueue events_;
  DaemonState state_;

  CameraSupervisor camera_;
  std::unique_ptr<RigSession> rig_;
  std::optional<Calibration> calibration_;
  std::unique_ptr<StackWorker> worker_;
  CaptureSchedule schedule_;
  HealthMonitor health_;
  BracketWatchdog watchdog_{health_};
  InclinometerFaults inclinometer_{clock_};
  IlluminanceSession illuminance_;
  OutputTree output_;
  RetentionScheduler retention_;
  bool day_budget_checked_ = false;  // the settings check of max_use_gib (day_budget.h) was made

  std::deque<CaptureTrigger> requests_;  // button presses and SIGUSR1, in order
  std::uint64_t stacks_done_ = 0;
  bool stopping_ = false;
  std::optional<SteadyTime> last_publish_;  // for the time paused
};

}  // namespace glarecam::daemon
