// glarecamd's core: the only long-lived owner of the rig's hardware. One event loop (one thread)
// captures on schedule (a fixed interval, the α targets as the sun moves, the operator's button,
// SIGUSR1), hands each bracket to the stack worker (written atomically, processed, the day's data
// sheet updated) and survives what a field throws at it:
//
//   camera lost       the stack is discarded, the camera reopened with capped exponential
//                     backoff (camera_supervisor.h); after camera_max_failures in a row run()
//                     fails (kHardware) and systemd restarts the daemon
//   inclinometer      a failed read or an implausible tilt: the stack is taken with α unknown,
//                     or capture pauses, per [faults] inclinometer
//   disk              below the reserve or read-only: capture pauses, resumes when space returns
//   clock             not synchronised: said in STATUS, and every stack flagged
//
// systemd (service_notifier.h): READY=1 once the camera is open, STATUS= whenever the status
// line changes, WATCHDOG=1 from the loop itself at half the watchdog interval, only while the loop
// runs and the worker is not stuck (a wedged camera blocks the loop, so the heartbeat stops and
// systemd restarts the daemon), STOPPING=1 on SIGTERM, after which queued stacks are written and
// run() returns. SIGHUP reloads the config (a bad one is reported and the old one kept).
//
// Everything the daemon touches is injected (DaemonServices): tests run it on a manual clock with
// a scripted camera, disk and notifier, one thread, no sleeping.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "core/error.h"
#include "daemon/camera_supervisor.h"
#include "daemon/daemon_clock.h"
#include "daemon/daemon_events.h"
#include "daemon/daemon_status.h"
#include "daemon/disk_space.h"
#include "daemon/service_notifier.h"
#include "daemon/stack_worker.h"
#include "rig/gpio/rig_io.h"
#include "rig/gpio/status_led.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"

namespace glarecam::daemon {

using RigIoOpener = std::function<Result<std::unique_ptr<rig::RigIo>>(const rig::RigIoConfig&)>;

struct DaemonServices {
  DaemonClock* clock = nullptr;
  ServiceNotifier* notifier = nullptr;
  DiskProbe* disk = nullptr;
  CameraOpener open_camera{};  // default capture::openCamera
  RigIoOpener open_rig_io{};   // default rig::openRigIo
  StackWorker::Mode worker_mode = StackWorker::Mode::kThread;
  bool watch_button = true;  // a thread polls the button (tests post ButtonEvents instead)
  std::function<void()> worker_job_hook{};  // tests: runs at the start of every worker job
};

struct DaemonOptions {
  std::filesystem::path config_path = rig::kDefaultRigConfigPath;
  std::optional<std::filesystem::path> output_root{};  // overrides [output] root
  std::optional<std::chrono::seconds> interval{};      // overrides [schedule]: a fixed interval
  std::optional<std::uint64_t> max_stacks{};  // stop once this many stacks are done (tests, demos)
};

// How often the loop looks at the disk while nothing else wakes it.
inline constexpr std::chrono::seconds kDiskCheckPeriod{10};
// A worker job running longer than this is stuck (a hung disk): the watchdog is no longer fed.
inline constexpr std::chrono::minutes kWorkerStallLimit{15};
// A wall clock that moved this much against the steady clock jumped: the schedule is replanned.
inline constexpr std::chrono::seconds kWallClockJump{5};
// How far ahead the α targets are computed, and how soon again when none lies in it.
inline constexpr std::chrono::hours kAlphaPlanHorizon{24};
// While paused by the inclinometer, how soon it is read again.
inline constexpr std::chrono::seconds kInclinometerRetry{30};

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

  Status start();
  Status step();
  void stop();

  // Opening and reopening the hardware and the output.
  void applyConfig();
  void openSensors();
  void openRigIo();
  void closeRigIo();
  // The output directories; `clean`: also remove what a killed run left half-written (at start
  // only: later the worker may be writing).
  void prepareOutput(bool clean);
  bool outputWritable();
  void retryInclinometer();
  void checkWallClock(SteadyTime now);
  Status checkConfig(const Config& config) const;
  Status checkReloadedCamera(const Config& config);
  void catchUp();
  Status reopenCamera(SteadyTime now);

  // One capture, and its parts.
  Status capture(CaptureTrigger trigger);
  std::optional<rig::RigGeometry> measureGeometry(capture::CaptureSettings& settings, bool& pause);
  capture::CaptureSettings baseSettings() const;
  Status cameraFailed(const Error& error, SteadyTime now, bool mid_bracket);
  void finishStack(capture::CapturedStack& stack, const std::optional<rig::RigGeometry>& geometry,
                   CaptureTrigger trigger, UtcTime bracket_start, UtcTime bracket_end);

  // The schedule.
  // `slot_taken`: the scheduled slot was just used (or skipped): the next one.
  void planNext(SteadyTime now, bool slot_taken);
  void planAlphaTargets(UtcTime from);
  std::optional<sun::ModuleOrientation> plannedModule();
  bool scheduledDue(SteadyTime now) const;
  // Ready, a camera open, not stopping and --count not reached: a due capture is taken now.
  bool mayCapture() const;
  SteadyTime nextDeadline(SteadyTime now) const;

  void handle(const DaemonEvent& event);
  void handleWorker(const WorkerEvent& event);
  void reload();
  void checkDisk(SteadyTime now);
  void checkClock();
  void feedWatchdog(SteadyTime now);
  bool healthy(SteadyTime now) const;
  void publishStatus();

  DaemonOptions options_;
  DaemonServices services_;
  Config config_;
  DaemonClock& clock_;
  EventQueue events_;
  DaemonState state_;

  CameraSupervisor camera_;
  std::unique_ptr<rig::RigSensors> sensors_;
  std::optional<rig::RigGeometry> last_geometry_;
  std::optional<double> scene_alpha_deg_;  // the last α measured: what a simulated camera shows
  std::set<std::string> logged_warnings_;  // the sensors' standing warnings, logged once
  std::optional<Calibration> calibration_;
  std::unique_ptr<rig::RigIo> io_;
  std::unique_ptr<rig::StatusLed> led_;
  std::jthread button_thread_;
  std::unique_ptr<StackWorker> worker_;

  std::optional<std::chrono::microseconds> watchdog_interval_;
  SteadyTime next_watchdog_{};
  SteadyTime next_disk_check_{};
  std::optional<SteadyTime> next_scheduled_;
  std::optional<SteadyTime> replan_at_;
  std::optional<SteadyTime> inclinometer_retry_at_;
  std::optional<UtcTime> planned_crossing_;  // the next α target's crossing, in wall time
  std::optional<UtcTime> last_interval_start_;
  std::map<double, UtcTime> taken_targets_;  // when each α target's slot was last used
  std::deque<CaptureTrigger> requests_;      // button presses and SIGUSR1, in order
  std::uint64_t stacks_done_ = 0;
  bool stopping_ = false;
};

}  // namespace glarecam::daemon
