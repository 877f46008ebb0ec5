#include "daemon/capture_daemon.h"

#include <fmt/format.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "capture/camera_registry.h"
#include "daemon/hardware/simulated_rig.h"
#include "daemon/journal_sink.h"
#include "daemon/storage/day_budget.h"
#include "daemon/storage/earlier_run.h"
#include "rig/gpio/button_debouncer.h"
#include "rig/gpio/rig_io_registry.h"

namespace glarecam::daemon {

namespace {

const char* triggerName(CaptureTrigger trigger) {
  switch (trigger) {
    case CaptureTrigger::kSchedule:
      return "schedule";
    case CaptureTrigger::kButton:
      return "button";
    case CaptureTrigger::kSignal:
      break;
  }
  return "signal";
}

std::string stackTag(const capture::CapturedStack& stack) {
  return stack.manifest.id.value_or("stack");
}

}  // namespace

Config effectiveConfig(Config config, const DaemonOptions& options) {
  if (options.output_root) config.daemon.output.root = *options.output_root;
  if (options.interval) {
    config.daemon.schedule.mode = ScheduleMode::kInterval;
    config.daemon.schedule.interval = *options.interval;
  }
  if (options.status_listen) config.daemon.status.listen = options.status_listen;
  if (options.max_use_bytes)
    config.daemon.output.retention = RetentionPolicy{.max_use_bytes = options.max_use_bytes};
  if (options.reserve_bytes) config.daemon.output.reserve_bytes = *options.reserve_bytes;
  return config;
}

Result<std::unique_ptr<CaptureDaemon>> CaptureDaemon::create(DaemonOptions options,
                                                             DaemonServices services) {
  if (!services.clock || !services.notifier || !services.disk)
    return fail(ErrorCode::kInternal, "glarecamd: a service is missing");
  if (!services.open_camera) services.open_camera = capture::openCamera;
  if (!services.open_rig_io) services.open_rig_io = rig::openRigIo;
  Config config;
  GLARECAM_ASSIGN(config, readConfig(options.config_path));
  return std::unique_ptr<CaptureDaemon>(
      new CaptureDaemon(std::move(options), std::move(services), std::move(config)));
}

CaptureDaemon::CaptureDaemon(DaemonOptions options, DaemonServices services, Config config)
    : options_(std::move(options)),
      services_(std::move(services)),
      config_(effectiveConfig(std::move(config), options_)),
      clock_(*services_.clock),
      events_(clock_),
      camera_(config_.daemon.faults, services_.open_camera,
              [this] { return rig_ ? rig_->sceneState() : capture::SceneState{}; }),
      schedule_(config_.daemon.schedule),
      health_(clock_, *services_.notifier, *services_.disk),
      output_(config_.daemon.output.root),
      retention_(clock_, config_.daemon.output, siteLongitude()) {}

CaptureDaemon::~CaptureDaemon() { stop(); }

// ---- the loop -------------------------------------------------------------------------------

Status CaptureDaemon::run() {
  GLARECAM_CHECK(start());
  while (!stopping_) {
    const Status stepped = step();
    if (!stepped) {
      stop();
      return stepped;
    }
  }
  stop();
  return {};
}

Status CaptureDaemon::start() {
  health_.start();
  GLARECAM_CHECK(checkConfig(config_));
  worker_ = std::make_unique<StackWorker>(WorkerOptions{}, events_, clock_, services_.worker_mode,
                                          services_.worker_job_hook);
  prepareOutput(true);
  applyConfig();
  spdlog::info("glarecamd: {} with camera {}, output {}", schedule_.describe(), *config_.rig.camera,
               output_.root().string());
  retention_.start(state_);  // before the recall: what it deletes is not shown
  checkDayBudget();
  EarlierRun earlier = EarlierRun::read(output_, clock_.utcNow(), siteLongitude());
  earlier.recordInto(state_);
  // Catch-up: the stacks an earlier run left unprocessed go to the worker first.
  for (std::filesystem::path& stack : earlier.unprocessed) worker_->submitWritten(std::move(stack));
  publishStatus();
  return {};
}

Status CaptureDaemon::step() {
  const SteadyTime now = clock_.now();
  if (watchdog_.feed(workerBusySince())) ++state_.watchdog_pings;
  if (now >= health_.nextDiskCheck()) {
    checkDisk();
    checkClock();
    checkWallClock();
  }
  if (inclinometer_.retryAt() && now >= *inclinometer_.retryAt())
    inclinometer_.retry(*rig_, config_.daemon.faults, state_);
  const auto retry = camera_.retryAt();
  if (!camera_.camera() && (!retry || now >= *retry)) GLARECAM_CHECK(reopenCamera(now));
  if (schedule_.replanAt() && now >= *schedule_.replanAt()) planNext(std::nullopt);
  if (mayCapture()) {
    if (!requests_.empty()) {
      const CaptureTrigger trigger = requests_.front();
      requests_.pop_front();
      GLARECAM_CHECK(capture(trigger));
    } else if (schedule_.due(now)) {
      GLARECAM_CHECK(capture(CaptureTrigger::kSchedule));
    }
  }
  publishStatus();
  if (stopping_) return {};
  const std::optional<DaemonEvent> event = events_.waitPop(nextDeadline(clock_.now()));
  if (event) handle(*event);
  while (!stopping_) {
    const std::optional<DaemonEvent> more = events_.tryPop();
    if (!more) break;
    handle(*more);
  }
  return {};
}

void CaptureDaemon::stop() {
  if (!worker_) return;
  if (!state_.stopping) {
    state_.stopping = true;
    services_.notifier->notify("STOPPING=1");
  }
  const std::size_t pending = worker_->pending();
  state_.status.clear();
  publishStatus();
  if (pending) spdlog::info("glarecamd: stopping; writing {} queued stacks", pending);
  worker_->stop();
  while (const std::optional<DaemonEvent> event = events_.tryPop()) {
    if (const auto* report = std::get_if<WorkerEvent>(&*event)) handleWorker(*report);
  }
  closeGpio();
  illuminance_.close();
  camera_.close();
  worker_.reset();
  spdlog::info("glarecamd: stopped after {} stacks ({} written, {} processed, {} failed)",
               state_.stacks_captured, state_.stacks_written, state_.stacks_processed,
               state_.stacks_failed);
}

void CaptureDaemon::handle(const DaemonEvent& event) {
  if (const auto* signal = std::get_if<SignalEvent>(&event)) {
    if (signal->signal == SIGTERM || signal->signal == SIGINT) {
      spdlog::info("glarecamd: {} received: stopping",
                   signal->signal == SIGTERM ? "SIGTERM" : "SIGINT");
      stopping_ = true;
      state_.stopping = true;
      services_.notifier->notify("STOPPING=1");
    } else if (signal->signal == SIGHUP) {
      reload();
    } else if (signal->signal == SIGUSR1) {
      requests_.push_back(CaptureTrigger::kSignal);
    }
  } else if (const auto* button = std::get_if<ButtonEvent>(&event)) {
    if (button->error) {
      state_.gpio_fault = button->error->message;
      spdlog::error("glarecamd: button: {}", button->error->message);
    } else if (config_.daemon.schedule.button) {
      if (rig_ && rig_->io()) state_.gpio_fault.clear();  // the button reads again
      requests_.push_back(CaptureTrigger::kButton);
    } else {
      spdlog::info("glarecamd: button pressed; [schedule] button = false ignores it");
    }
  } else {
    handleWorker(std::get<WorkerEvent>(event));
  }
}

void CaptureDaemon::handleWorker(const WorkerEvent& event) {
  ScopedLogFields fields(LogFields{{"GLARECAM_STACK", event.stack_id}});
  recordWorkerEvent(state_, event, worker_->hasParked());
  // A stack done is a stack that retention may now take, and one more for the budget.
  if (event.last && !event.error) {
    retention_.apply(state_);
    if (!day_budget_checked_) checkDayBudget();
  }
  if (event.last && event.captured && options_.max_stacks &&
      ++stacks_done_ >= *options_.max_stacks && !stopping_) {
    spdlog::info("glarecamd: {} stacks done: stopping", stacks_done_);
    stopping_ = true;
  }
}

bool CaptureDaemon::mayCapture() const {
  const bool enough = options_.max_stacks && state_.stacks_captured >= *options_.max_stacks;
  return state_.ready && camera_.camera() && !stopping_ && !enough;
}

SteadyTime CaptureDaemon::nextDeadline(SteadyTime now) const {
  SteadyTime deadline = health_.nextDiskCheck();
  const auto earliest = [&deadline](const std::optional<SteadyTime>& t) {
    if (t) deadline = std::min(deadline, *t);
  };
  earliest(health_.nextWatchdog());
  // Only a capture that can be taken wakes the loop: a due one that cannot would spin it.
  if (mayCapture()) earliest(schedule_.next());
  if (mayCapture() && !requests_.empty()) earliest(now);
  if (!camera_.camera()) earliest(camera_.retryAt().value_or(now));
  earliest(schedule_.replanAt());
  earliest(inclinometer_.retryAt());
  return std::max(deadline, now);
}

// ---- the config and what it opens -----------------------------------------------------------

Status CaptureDaemon::checkConfig(const Config& config) const {
  if (!config.rig.camera)
    return badInput(config.rig.path.string() + ": glarecamd needs camera = \"URI\"");
  const auto uri = capture::parseCameraUri(*config.rig.camera);
  if (!uri) return std::unexpected(withContext(uri.error(), config.rig.path.string() + ": camera"));
  return {};
}

// A new camera, or the camera with new options, must open as configured before the reload is
// taken: the old camera is released first (a GigE camera has one controller). One that is absent
// now may come back, like a camera lost at any other time.
Status CaptureDaemon::checkReloadedCamera(const Config& config) {
  GLARECAM_CHECK(checkConfig(config));
  const capture::CameraOptions options = capture::cameraOptions(config.daemon.capture);
  if (*config.rig.camera == config_.rig.camera &&
      options == capture::cameraOptions(config_.daemon.capture))
    return {};
  camera_.close();
  auto trial = services_.open_camera(*config.rig.camera, options, {});
  if (!trial && trial.error().code == ErrorCode::kBadInput)
    return std::unexpected(withContext(trial.error(), config.rig.path.string() + ": camera"));
  return {};
}

void CaptureDaemon::applyConfig() {
  const DaemonConfig& daemon = config_.daemon;
  camera_.configure(config_.rig.camera.value_or(""), capture::cameraOptions(daemon.capture),
                    daemon.faults);
  const auto calibration = rig::rigCameraCalibration(config_.rig);
  calibration_ = calibration ? *calibration : std::nullopt;
  if (!calibration) spdlog::error("glarecamd: {}", calibration.error().message);
  worker_->reconfigure({.day = {.root = daemon.output.root,
                                .module = daemon.output.module,
                                .longitude_deg = siteLongitude()},
                        .threads = daemon.output.processing_threads});
  output_ = OutputTree(daemon.output.root);
  retention_.configure(daemon.output, siteLongitude());
  schedule_.reconfigure(daemon.schedule);  // the slots taken so far stay taken
  prepareOutput(false);
  closeGpio();
  rig_ = std::make_unique<RigSession>(
      config_.rig,
      RigSessionOptions{.faults = daemon.faults, .open_rig_io = services_.open_rig_io});
  inclinometer_.open(*rig_, state_);
  illuminance_.open(config_.rig, state_);
  openGpio();
  checkClock();
  planNext(std::nullopt);
}

void CaptureDaemon::reload() {
  ScopedLogFields fields(LogFields{{"GLARECAM_EVENT", "reload"}});
  auto config = readConfig(options_.config_path);
  if (config) {
    config = effectiveConfig(std::move(*config), options_);
    const Status checked = checkReloadedCamera(*config);
    if (!checked) config = std::unexpected(checked.error());
  }
  if (!config) {
    state_.config_warning =
        fmt::format("reload failed, the previous config stays: {}", config.error().message);
    spdlog::error("glarecamd: {}", state_.config_warning);
    return;
  }
  if (config->daemon.status.listen != config_.daemon.status.listen)
    spdlog::warn("glarecamd: [status] listen changed; the status page moves at the next start");
  config_ = std::move(*config);
  state_.config_warning.clear();
  ++state_.reloads;
  applyConfig();
  checkDayBudget();  // a new budget or schedule
  spdlog::info("glarecamd: reloaded {}", options_.config_path.string());
}

void CaptureDaemon::openGpio() {
  state_.gpio_fault.clear();
  const Status opened = rig_->openGpio();
  if (!opened) {  // the rig measures on without its LED and button
    state_.gpio_fault = opened.error().message;
    spdlog::error("glarecamd: {}; running without GPIO", opened.error().message);
    return;
  }
  if (!services_.watch_button) return;
  rig_->watchButton([this] { events_.post(ButtonEvent{}); },
                    [this](const Error& error) { events_.post(ButtonEvent{.error = error}); });
}

void CaptureDaemon::closeGpio() {
  if (rig_) rig_->closeGpio();
}

void CaptureDaemon::prepareOutput(bool clean) {
  const Status made = output_.prepare();
  if (!made) {
    state_.disk_fault = made.error().message;
    spdlog::error("glarecamd: {}", made.error().message);
    return;
  }
  if (!clean) return;
  // Whatever a killed glarecamd left half-written (the worker has not started yet).
  if (const std::size_t removed = output_.removeLeftovers())
    spdlog::warn("glarecamd: removed {} half-written files of an earlier run", removed);
}

std::optional<double> CaptureDaemon::siteLongitude() const {
  return config_.rig.site ? std::optional(config_.rig.site->longitude_deg) : std::nullopt;
}

Status CaptureDaemon::reopenCamera(SteadyTime now) {
  const auto opened = camera_.acquire(now);
  if (!opened) {
    // Before the first open, a camera the config cannot name is the config's problem.
    if (opened.error().code == ErrorCode::kBadInput && !state_.ready)
      return std::unexpected(withContext(opened.error(), config_.rig.path.string() + ": camera"));
    return cameraFailed(opened.error(), now, false);
  }
  if (!state_.camera_fault.empty())
    spdlog::info("glarecamd: camera {} open again", (*opened)->info().uri);
  state_.camera_fault.clear();
  if (!state_.ready) {
    state_.ready = true;
    spdlog::info("glarecamd: ready: camera {} ({} {})", (*opened)->info().uri,
                 (*opened)->info().vendor, (*opened)->info().model);
    services_.notifier->notify("READY=1");
  }
  return {};
}

Status CaptureDaemon::cameraFailed(const Error& error, SteadyTime now, bool mid_bracket) {
  if (mid_bracket) camera_.failed(error, now);  // acquire() counted an open that failed
  if (camera_.exhausted())
    return hardwareError(fmt::format("glarecamd: the camera failed {} times in a row; last: {}",
                                     camera_.failures(), error.message));
  state_.camera_fault = camera_.faultText(error, now, mid_bracket);
  spdlog::error("glarecamd: camera: {}", state_.camera_fault);
  return {};
}

// ---- one capture ----------------------------------------------------------------------------

Status CaptureDaemon::capture(CaptureTrigger trigger) {
  ScopedLogFields fields(
      LogFields{{"GLARECAM_EVENT", "capture"}, {"GLARECAM_TRIGGER", triggerName(trigger)}});
  // The stack's time: α measured at its start (a simulated camera draws that α), the bracket
  // timed on it (a time lapse runs it at real rate: daemon_clock.h).
  const StackTimeline timeline(clock_);
  const std::optional<double> target_deg =
      trigger == CaptureTrigger::kSchedule ? schedule_.nextTargetDeg() : std::nullopt;
  const Status taken = takeStack(trigger, timeline, target_deg);
  // The slot is used, or skipped for good, once its stack is done: until then it is the one the
  // status names next, and a target the sun crossed meanwhile is still owed.
  if (trigger == CaptureTrigger::kSchedule) {
    schedule_.take(timeline.begun());
    planNext(timeline.begun());
  }
  return taken;
}

Status CaptureDaemon::takeStack(CaptureTrigger trigger, const StackTimeline& timeline,
                                std::optional<double> target_deg) {
  const auto skip = [this](std::string reason) -> Status {
    ++state_.captures_skipped;
    if (reason != state_.skip_reason) spdlog::warn("glarecamd: no stack: {}", reason);
    state_.skip_reason = std::move(reason);
    return {};
  };
  checkDisk();  // before every capture: a disk that filled since the last look
  if (!state_.disk_fault.empty()) return skip("capture paused for the disk");
  if (worker_->full()) return skip("the worker is still writing the earlier stacks");
  checkClock();
  capture::CaptureSettings settings = capture::captureSettings(config_.daemon.capture);
  settings.calibration = calibration_;
  if (config_.daemon.output.module != kUnnamedModule)
    settings.module = config_.daemon.output.module;
  settings.alpha_from_scene = !rig_->measuresAlpha();
  settings.source_illuminance = rig_->config().fixed_source_illuminance;  // a lab lamp's
  const InclinometerFaults::Measured measured =
      inclinometer_.measure(*rig_, config_.daemon.faults, state_, settings, timeline.begun());
  if (measured.pause) return skip("capture paused for the inclinometer");
  const std::optional<rig::RigGeometry>& geometry = measured.geometry;
  if (trigger == CaptureTrigger::kSchedule && geometry) {
    if (geometry->sun && geometry->sun->elevation_deg <= 0) return skip("the sun is down");
    if (!target_deg && geometry->alpha_deg >= config_.daemon.schedule.max_alpha_deg)
      return skip(fmt::format("α {:.1f}° is beyond max_alpha_deg {:g}°", geometry->alpha_deg,
                              config_.daemon.schedule.max_alpha_deg));
  }
  const SteadyTime now = clock_.now();
  const auto acquired = camera_.acquire(now);
  if (!acquired) return cameraFailed(acquired.error(), now, false);
  state_.skip_reason.clear();
  state_.capturing = true;
  publishStatus();
  // The loop cannot ping during the bracket: a ping due before its expected end goes now.
  if (watchdog_.feedBeforeBracket(settings, workerBusySince())) ++state_.watchdog_pings;
  const UtcTime start = timeline.now();
  settings.start_time = start;
  const SteadyTime bracket_start = clock_.now();
  illuminance_.startBracket(start, state_);
  auto stack = capture::captureStack(**acquired, settings);
  if (stack) watchdog_.recordBracket(clock_.now() - bracket_start);
  const UtcTime end = timeline.now();
  // The source illuminance sampled during the bracket (none: unreferred), only ever its own.
  const std::optional<SourceIlluminance> source = illuminance_.finishBracket(end, state_);
  if (stack && source) stack->manifest.source_illuminance = source;
  state_.capturing = false;
  if (!stack) {
    const ErrorCode code = stack.error().code;
    if (code == ErrorCode::kHardware || code == ErrorCode::kIo)
      return cameraFailed(stack.error(), clock_.now(), true);
    ++state_.stacks_failed;  // the scene, not the camera (too dark to meter, say)
    state_.worker_fault = stack.error().message;
    spdlog::error("glarecamd: the bracket failed: {}", stack.error().message);
    return {};
  }
  camera_.succeeded();
  finishStack(*stack, geometry, trigger, start, end);
  if (target_deg) stack->manifest.source["daemon"]["target_alpha_deg"] = *target_deg;
  state_.last_stack = stackTag(*stack);
  state_.last_alpha_deg = stack->manifest.alpha_deg;
  state_.last_capture_time = start;
  ++state_.stacks_captured;
  {
    ScopedLogFields stack_fields(LogFields{{"GLARECAM_STACK", stackTag(*stack)}});
    spdlog::info("glarecamd: captured {} ({} frames{})", stackTag(*stack), stack->frames.size(),
                 stack->manifest.alpha_deg ? fmt::format(", α {:.2f}°", *stack->manifest.alpha_deg)
                                           : std::string(", α unknown"));
  }
  if (!worker_->submit(std::move(*stack))) spdlog::error("glarecamd: the worker refused a stack");
  return {};
}

void CaptureDaemon::finishStack(capture::CapturedStack& stack,
                                const std::optional<rig::RigGeometry>& geometry,
                                CaptureTrigger trigger, UtcTime bracket_start,
                                UtcTime bracket_end) {
  if (geometry) rig_->recordBracketMiddle(stack, *geometry, bracket_start, bracket_end);
  nlohmann::json flags = nlohmann::json::array();
  if (!state_.clock_warning.empty()) flags.push_back("clock_unsynchronised");
  if (!geometry && rig_->measuresAlpha()) flags.push_back("alpha_unknown");
  if (illuminance_.configured() && !stack.manifest.source_illuminance)
    flags.push_back("source_illuminance_unknown");
  stack.manifest.source["daemon"] = {
      {"trigger", triggerName(trigger)},
      {"schedule", schedule_.describe()},
      {"flags", std::move(flags)},
  };
}

// ---- the schedule and the checks --------------------------------------------------------------

void CaptureDaemon::planNext(std::optional<UtcTime> slot_taken) {
  CaptureSchedule::Geometry geometry{.site = config_.rig.site, .module = std::nullopt};
  if (schedule_.config().mode == ScheduleMode::kAlphaTargets) {
    // The module's orientation from the last measurement, else one now.
    if (!rig_->lastGeometry() && rig_->sensorsOpen()) {
      const auto measured = rig_->measure(clock_.utcNow(), clock_.clockStatus());
      if (!measured) spdlog::warn("glarecamd: α targets: {}", measured.error().message);
    }
    if (rig_->lastGeometry()) geometry.module = rig_->lastGeometry()->module;
  }
  schedule_.plan(clock_, slot_taken, geometry);
  if (!schedule_.unplannedReason().empty()) state_.skip_reason = schedule_.unplannedReason();
  state_.next_target_deg = schedule_.nextTargetDeg();
  state_.next_capture_time = schedule_.nextWallTime(clock_);
}

void CaptureDaemon::checkWallClock() {
  const auto jumped = schedule_.wallClockJump(clock_);
  if (!jumped) return;
  spdlog::warn("glarecamd: the wall clock jumped by {:.0f} s; the α targets are planned again",
               std::chrono::duration<double>(*jumped).count());
  planNext(std::nullopt);
}

void CaptureDaemon::checkDisk() {
  // Below the reserve with a space budget set, retention frees what it may first.
  const HealthMonitor::DiskCheck disk = retention_.checkDisk(health_, state_);
  if (disk.state) state_.disk = disk.state;
  std::string reason = disk.pause_reason;
  const bool kept = worker_ && worker_->hasParked();
  if (kept && reason.empty()) {
    // statvfs cannot see every refusal: a probe write first, then the kept stacks. The fault
    // ends when they are written (handleWorker).
    if (output_.writable()) worker_->retryParked();
    return;
  }
  if (reason.empty() && isKeptStackFault(state_.disk_fault)) return;  // being retried
  if (reason.empty() && !state_.disk_fault.empty() && !output_.writable())
    reason = state_.disk_fault;
  if (reason == state_.disk_fault) return;
  if (reason.empty())
    spdlog::info("glarecamd: disk: {} free; capture resumes", formatBytes(disk.state->free_bytes));
  else
    spdlog::error("glarecamd: disk: {}; capture pauses", reason);
  state_.disk_fault = std::move(reason);
}

void CaptureDaemon::checkDayBudget() {
  const std::optional<std::uint64_t> budget = config_.daemon.output.retention.max_use_bytes;
  if (!budget) {  // none, or a reload took it away
    state_.retention_budget_warning.clear();
    day_budget_checked_ = true;
    return;
  }
  const std::optional<std::uint64_t> stack_bytes = newestStackBytes(output_);
  if (!stack_bytes) return;  // nothing to measure yet: after the first stack
  day_budget_checked_ = true;
  // The solar day's start in UTC, and the wall seconds per steady second (a time lapse).
  const UtcTime now = clock_.utcNow();
  const auto day = parseIsoDay(solarDay(now, siteLongitude()));
  if (!day) return;
  const auto offset = std::chrono::duration_cast<UtcTime::duration>(
      std::chrono::duration<double>(siteLongitude().value_or(0.0) / 15.0 * 3600.0));
  const UtcTime day_start = UtcTime(*day) - offset;
  const auto steady_hour = clock_.steadyAt(now + std::chrono::hours(1)) - clock_.steadyAt(now);
  const double wall_per_steady =
      3600.0 / std::max(std::chrono::duration<double>(steady_hour).count(), 1e-9);
  const std::optional<sun::ModuleOrientation> module =
      rig_ && rig_->lastGeometry() ? std::optional(rig_->lastGeometry()->module) : std::nullopt;
  const auto estimate = estimateDayStacks(config_.daemon.schedule, config_.rig.site, module,
                                          day_start, wall_per_steady);
  const auto warning = estimate ? dayBudgetWarning(*budget, *estimate, *stack_bytes) : std::nullopt;
  state_.retention_budget_warning = warning.value_or("");
  if (warning) spdlog::warn("glarecamd: retention: {}", *warning);
}

void CaptureDaemon::checkClock() {
  if (!config_.rig.site) return;  // only the sun's position needs the wall clock
  std::string warning = HealthMonitor::clockWarning(clockStatus());
  if (warning != state_.clock_warning && !warning.empty())
    spdlog::warn("glarecamd: clock {}", warning);
  state_.clock_warning = std::move(warning);
}

sun::ClockStatus CaptureDaemon::clockStatus() const {
  return rigClockStatus(config_.rig, clock_.clockStatus());
}

std::optional<SteadyTime> CaptureDaemon::workerBusySince() const {
  return worker_ ? worker_->busySince() : std::nullopt;
}

void CaptureDaemon::publishStatus() {
  const SteadyTime now = clock_.now();
  if (last_publish_ && capturePaused(state_))
    state_.paused_seconds += std::chrono::duration<double>(now - *last_publish_).count();
  last_publish_ = now;
  state_.led = ledState(state_, state_.capturing);
  if (rig_) rig_->show(state_.led);
  std::string line = statusLine(state_, schedule_.describe());
  if (line != state_.status) {
    state_.status = std::move(line);
    services_.notifier->notify("STATUS=" + state_.status);
    spdlog::debug("glarecamd: status: {}", state_.status);
  }
  if (services_.status_board) services_.status_board->publish(snapshot());
}

StatusSnapshot CaptureDaemon::snapshot() const {
  const OutputConfig& output = config_.daemon.output;
  const UtcTime now = clock_.utcNow();
  return {.state = state_,
          .schedule = schedule_.describe(),
          .camera_uri = config_.rig.camera.value_or(""),
          .camera_open = camera_.camera() != nullptr,
          .inclinometer_uri = config_.rig.inclinometer ? config_.rig.inclinometer->uri : "",
          .clock_synchronised = clockStatus().synchronised,
          .simulated_time = clock_.simulated(),
          .output_root = output.root,
          .reserve_bytes = output.reserve_bytes,
          .retention_policy = retention_.policyText(),
          .now = now,
          .today = solarDay(now, siteLongitude())};
}

}  // namespace glarecam::daemon
