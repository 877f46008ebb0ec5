#include "daemon/capture_daemon.h"

#include <fmt/format.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <condition_variable>

#include "capture/camera_registry.h"
#include "core/atomic_file.h"
#include "daemon/alpha_schedule.h"
#include "daemon/journal_sink.h"
#include "daemon/rig_stack.h"
#include "rig/gpio/button_debouncer.h"
#include "rig/gpio/rig_io_registry.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

namespace {

// How a disk fault from a failed write begins: it ends only when the kept stack is written.
constexpr std::string_view kWriteFailed = "writing a stack failed: ";
// After a failed button read, how long the button thread waits before reading again.
constexpr std::chrono::seconds kButtonRetry{5};

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

std::string scheduleText(const ScheduleConfig& schedule) {
  switch (schedule.mode) {
    case ScheduleMode::kInterval:
      return fmt::format("every {} s", schedule.interval.count());
    case ScheduleMode::kAlphaTargets:
      return fmt::format("at {} α targets", schedule.alpha_targets_deg.size());
    case ScheduleMode::kButton:
      break;
  }
  return "on the button and SIGUSR1";
}

std::string stackTag(const capture::CapturedStack& stack) {
  return stack.manifest.id.value_or("stack");
}

}  // namespace

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
      config_(std::move(config)),
      clock_(*services_.clock),
      events_(clock_),
      camera_(config_.daemon.faults, services_.open_camera, [this] { return scene_alpha_deg_; }) {
  if (options_.output_root) config_.daemon.output.root = *options_.output_root;
  if (options_.interval) {
    config_.daemon.schedule.mode = ScheduleMode::kInterval;
    config_.daemon.schedule.interval = *options_.interval;
  }
}

CaptureDaemon::~CaptureDaemon() { stop(); }

// ---- running --------------------------------------------------------------------------------

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
  watchdog_interval_ = services_.notifier->watchdogInterval();
  const SteadyTime now = clock_.now();
  next_watchdog_ = now;
  GLARECAM_CHECK(checkConfig(config_));
  worker_ = std::make_unique<StackWorker>(WorkerOptions{}, events_, clock_, services_.worker_mode,
                                          services_.worker_job_hook);
  prepareOutput(true);
  applyConfig();
  spdlog::info("glarecamd: {} with camera {}, output {}", scheduleText(config_.daemon.schedule),
               *config_.rig.camera, config_.daemon.output.root.string());
  catchUp();
  publishStatus();
  return {};
}

Status CaptureDaemon::step() {
  const SteadyTime now = clock_.now();
  feedWatchdog(now);
  if (now >= next_disk_check_) {
    checkDisk(now);
    checkClock();
    checkWallClock(now);
  }
  if (inclinometer_retry_at_ && now >= *inclinometer_retry_at_) retryInclinometer();
  const auto retry = camera_.retryAt();
  if (!camera_.camera() && (!retry || now >= *retry)) GLARECAM_CHECK(reopenCamera(now));
  if (replan_at_ && now >= *replan_at_) planNext(now, false);
  if (mayCapture()) {
    if (!requests_.empty()) {
      const CaptureTrigger trigger = requests_.front();
      requests_.pop_front();
      GLARECAM_CHECK(capture(trigger));
    } else if (scheduledDue(now)) {
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
  closeRigIo();
  camera_.close();
  worker_.reset();
  spdlog::info("glarecamd: stopped after {} stacks ({} written, {} processed, {} failed)",
               state_.stacks_captured, state_.stacks_written, state_.stacks_processed,
               state_.stacks_failed);
}

// ---- configuration and hardware ----------------------------------------------------------------

void CaptureDaemon::applyConfig() {
  const DaemonConfig& daemon = config_.daemon;
  camera_.configure(config_.rig.camera.value_or(""), capture::cameraOptions(daemon.capture),
                    daemon.faults);
  const auto calibration = rig::rigCameraCalibration(config_.rig);
  calibration_ = calibration ? *calibration : std::nullopt;
  if (!calibration) spdlog::error("glarecamd: {}", calibration.error().message);
  worker_->reconfigure(
      {.day = {.root = daemon.output.root,
               .module = daemon.output.module,
               .longitude_deg = config_.rig.site ? std::optional(config_.rig.site->longitude_deg)
                                                 : std::nullopt},
       .threads = daemon.output.processing_threads});
  prepareOutput(false);
  openSensors();
  closeRigIo();
  openRigIo();
  checkClock();
  planNext(clock_.now(), false);
}

void CaptureDaemon::openSensors() {
  sensors_.reset();
  last_geometry_.reset();  // the module may have moved, or the config's geometry changed
  logged_warnings_.clear();
  if (!config_.rig.site && !config_.rig.fixed_source) return;  // α is not measured
  auto sensors = rig::RigSensors::open(config_.rig);
  if (!sensors) {
    if (sensors.error().message != state_.inclinometer_fault)
      spdlog::error("glarecamd: {}", sensors.error().message);
    state_.inclinometer_fault = sensors.error().message;
    return;
  }
  sensors_ = std::move(*sensors);
  state_.inclinometer_fault.clear();
}

void CaptureDaemon::openRigIo() {
  state_.gpio_fault.clear();
  if (!config_.rig.gpio) return;
  auto io = services_.open_rig_io(*config_.rig.gpio);
  if (!io) {  // the rig measures on without its LED and button
    state_.gpio_fault = io.error().message;
    spdlog::error("glarecamd: {}; running without GPIO", io.error().message);
    return;
  }
  io_ = std::move(*io);
  spdlog::info("glarecamd: GPIO {}", io_->description());
  led_ = std::make_unique<rig::StatusLed>(*io_);
  led_->start();
  if (!services_.watch_button || !io_->hasButton()) return;
  button_thread_ = std::jthread(
      [this, io = io_.get(), debounce = config_.rig.gpio->debounce](std::stop_token stop) {
        rig::ButtonWatcher watcher(*io, debounce);
        std::mutex mutex;
        std::condition_variable_any pause;
        while (!stop.stop_requested()) {
          const auto pressed = watcher.waitForPress(rig::RigClock::time_point::max(), stop);
          if (pressed && *pressed) events_.post(ButtonEvent{});
          if (pressed) continue;
          events_.post(ButtonEvent{.error = pressed.error()});
          std::unique_lock lock(mutex);
          pause.wait_for(lock, stop, kButtonRetry, [] { return false; });
        }
      });
}

void CaptureDaemon::closeRigIo() {
  if (button_thread_.joinable()) {
    button_thread_.request_stop();
    button_thread_.join();
  }
  if (led_) {
    const Status stopped = led_->stop();
    if (!stopped) spdlog::warn("glarecamd: {}", stopped.error().message);
  }
  led_.reset();
  io_.reset();
}

void CaptureDaemon::prepareOutput(bool clean) {
  const fs::path& root = config_.daemon.output.root;
  for (const char* directory : {kStacksDirectory, kResultsDirectory, kDaysDirectory}) {
    const Status made = ensureDirectory(root / directory);
    if (!made) {
      state_.disk_fault = made.error().message;
      spdlog::error("glarecamd: {}", made.error().message);
      return;
    }
  }
  if (!clean) return;
  // Whatever a killed glarecamd left half-written (the worker has not started yet).
  std::size_t removed = removeStaleTemporaries(root / kStacksDirectory);
  std::error_code error;
  for (const char* directory : {kResultsDirectory, kDaysDirectory}) {
    removed += removeStaleTemporaries(root / directory);
    for (const auto& entry : fs::directory_iterator(root / directory, error))
      if (entry.is_directory(error)) removed += removeStaleTemporaries(entry.path());
  }
  if (removed) spdlog::warn("glarecamd: removed {} half-written files of an earlier run", removed);
}

// After a failed write: do the directories exist, and does a directory made in stacks/ stick?
bool CaptureDaemon::outputWritable() {
  const fs::path& root = config_.daemon.output.root;
  for (const char* directory : {kStacksDirectory, kResultsDirectory, kDaysDirectory})
    if (!ensureDirectory(root / directory)) return false;
  std::string probe =
      (root / kStacksDirectory / (std::string(kTemporaryPrefix) + "probe-XXXXXX")).string();
  if (!mkdtemp(probe.data())) return false;
  std::error_code error;
  fs::remove(probe, error);
  return true;
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

Status CaptureDaemon::checkConfig(const Config& config) const {
  if (!config.rig.camera)
    return badInput(config.rig.path.string() + ": glarecamd needs camera = \"URI\"");
  const auto uri = capture::parseCameraUri(*config.rig.camera);
  if (!uri) return std::unexpected(withContext(uri.error(), config.rig.path.string() + ": camera"));
  return {};
}

void CaptureDaemon::catchUp() {
  const fs::path& root = config_.daemon.output.root;
  std::error_code error;
  std::vector<fs::path> stacks;
  for (const auto& entry : fs::directory_iterator(root / kStacksDirectory, error)) {
    const fs::path results = root / kResultsDirectory;
    const std::string id = entry.path().filename().string();
    if (entry.is_directory(error) && fs::exists(entry.path() / "stack.json", error) &&
        !fs::exists(results / id / "result.json", error) &&
        !fs::exists(results / (id + kFailedSuffix), error))
      stacks.push_back(entry.path());
  }
  std::sort(stacks.begin(), stacks.end());
  if (!stacks.empty())
    spdlog::info("glarecamd: processing {} stacks of an earlier run", stacks.size());
  for (fs::path& stack : stacks) worker_->submitWritten(std::move(stack));
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
  const int failures = camera_.failures();
  if (camera_.exhausted())
    return hardwareError(fmt::format("glarecamd: the camera failed {} times in a row; last: {}",
                                     failures, error.message));
  const auto retry = camera_.retryAt();
  const auto wait =
      retry ? std::chrono::ceil<std::chrono::seconds>(*retry - now) : std::chrono::seconds(0);
  state_.camera_fault = fmt::format("{}{}; reopening in {} s (failure {} of {})", error.message,
                                    mid_bracket ? "; the stack was discarded" : "", wait.count(),
                                    failures, camera_.maxFailures());
  spdlog::error("glarecamd: camera: {}", state_.camera_fault);
  return {};
}

void CaptureDaemon::reload() {
  ScopedLogFields fields(LogFields{{"GLARECAM_EVENT", "reload"}});
  auto config = readConfig(options_.config_path);
  if (config) {
    const Status checked = checkReloadedCamera(*config);
    if (!checked) config = std::unexpected(checked.error());
  }
  if (!config) {
    state_.config_warning =
        fmt::format("reload failed, the previous config stays: {}", config.error().message);
    spdlog::error("glarecamd: {}", state_.config_warning);
    return;
  }
  config_ = std::move(*config);
  if (options_.output_root) config_.daemon.output.root = *options_.output_root;
  if (options_.interval) {
    config_.daemon.schedule.mode = ScheduleMode::kInterval;
    config_.daemon.schedule.interval = *options_.interval;
  }
  state_.config_warning.clear();
  ++state_.reloads;
  applyConfig();
  spdlog::info("glarecamd: reloaded {}", options_.config_path.string());
}

// ---- one capture ----------------------------------------------------------------------------

capture::CaptureSettings CaptureDaemon::baseSettings() const {
  capture::CaptureSettings settings = capture::captureSettings(config_.daemon.capture);
  settings.calibration = calibration_;
  settings.alpha_from_scene = !config_.rig.site && !config_.rig.fixed_source;
  return settings;
}

std::optional<rig::RigGeometry> CaptureDaemon::measureGeometry(capture::CaptureSettings& settings,
                                                               bool& pause) {
  pause = false;
  if (!config_.rig.site && !config_.rig.fixed_source) return std::nullopt;
  if (!sensors_) openSensors();  // an inclinometer absent at start may have come back
  Result<rig::RigGeometry> measured =
      sensors_ ? sensors_->measureWithClock(clock_.utcNow(), clock_.clockStatus())
               : Result<rig::RigGeometry>(
                     std::unexpected(Error{ErrorCode::kHardware, state_.inclinometer_fault}));
  const FaultConfig& faults = config_.daemon.faults;
  if (measured && measured->tilt &&
      !(measured->tilt->module_tilt_deg >= faults.min_tilt_deg &&
        measured->tilt->module_tilt_deg <= faults.max_tilt_deg))
    measured = hardwareError(fmt::format(
        "{}: implausible tilt {:.2f}° (outside [{:g}, {:g}]°: a loose sensor, a moved rig?)",
        measured->inclinometer_uri, measured->tilt->module_tilt_deg, faults.min_tilt_deg,
        faults.max_tilt_deg));
  state_.inclinometer_pauses = faults.inclinometer == InclinometerFaultPolicy::kPause;
  if (measured) {
    if (!state_.inclinometer_fault.empty()) spdlog::info("glarecamd: the inclinometer reads again");
    state_.inclinometer_fault.clear();
    inclinometer_retry_at_.reset();
    for (const std::string& warning : measured->warnings)
      if (logged_warnings_.insert(warning).second) spdlog::warn("glarecamd: {}", warning);
    settings.alpha_deg = measured->alpha_deg;
    settings.geometry = rig::geometryJson(*measured);
    last_geometry_ = *measured;
    return std::move(*measured);
  }
  pause = state_.inclinometer_pauses;
  if (measured.error().message != state_.inclinometer_fault)
    spdlog::error("glarecamd: {}; {}", measured.error().message,
                  pause ? "capture pauses" : "the stack's α is unknown");
  state_.inclinometer_fault = measured.error().message;
  inclinometer_retry_at_ = clock_.now() + kInclinometerRetry;
  settings.geometry = nlohmann::json{{"alpha_unknown", measured.error().message}};
  return std::nullopt;
}

Status CaptureDaemon::capture(CaptureTrigger trigger) {
  ScopedLogFields fields(
      LogFields{{"GLARECAM_EVENT", "capture"}, {"GLARECAM_TRIGGER", triggerName(trigger)}});
  const std::optional<double> target_deg = state_.next_target_deg;
  if (trigger == CaptureTrigger::kSchedule) {  // this slot is used, or skipped for good
    if (target_deg) taken_targets_[*target_deg] = clock_.utcNow();
    planNext(clock_.now(), true);
  }
  const auto skip = [this](std::string reason) -> Status {
    ++state_.captures_skipped;
    if (reason != state_.skip_reason) spdlog::warn("glarecamd: no stack: {}", reason);
    state_.skip_reason = std::move(reason);
    return {};
  };
  checkDisk(clock_.now());  // before every capture: a disk that filled since the last look
  if (!state_.disk_fault.empty()) return skip("capture paused for the disk");
  if (worker_->full()) return skip("the worker is still writing the earlier stacks");
  checkClock();
  capture::CaptureSettings settings = baseSettings();
  bool pause = false;
  const std::optional<rig::RigGeometry> geometry = measureGeometry(settings, pause);
  if (pause) return skip("capture paused for the inclinometer");
  if (trigger == CaptureTrigger::kSchedule && geometry) {
    if (geometry->sun && geometry->sun->elevation_deg <= 0) return skip("the sun is down");
    if (!target_deg && geometry->alpha_deg >= config_.daemon.schedule.max_alpha_deg)
      return skip(fmt::format("α {:.1f}° is beyond max_alpha_deg {:g}°", geometry->alpha_deg,
                              config_.daemon.schedule.max_alpha_deg));
  }
  if (settings.alpha_deg) scene_alpha_deg_ = settings.alpha_deg;
  const SteadyTime now = clock_.now();
  const auto acquired = camera_.acquire(now);
  if (!acquired) return cameraFailed(acquired.error(), now, false);
  state_.skip_reason.clear();
  state_.capturing = true;
  publishStatus();
  feedWatchdog(now);
  const UtcTime start = clock_.utcNow();
  settings.start_time = start;
  auto stack = capture::captureStack(**acquired, settings);
  const UtcTime end = clock_.utcNow();
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
  if (trigger == CaptureTrigger::kSchedule && target_deg)
    stack->manifest.source["daemon"]["target_alpha_deg"] = *target_deg;
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
  if (geometry && sensors_) {
    const Status recorded =
        recordBracketGeometry(*sensors_, *geometry, stack, bracket_start, bracket_end);
    if (!recorded)
      spdlog::warn("glarecamd: α for the bracket's middle: {}", recorded.error().message);
  }
  nlohmann::json flags = nlohmann::json::array();
  if (!state_.clock_warning.empty()) flags.push_back("clock_unsynchronised");
  if (!geometry && (config_.rig.site || config_.rig.fixed_source)) flags.push_back("alpha_unknown");
  stack.manifest.source["daemon"] = {
      {"trigger", triggerName(trigger)},
      {"schedule", scheduleText(config_.daemon.schedule)},
      {"flags", std::move(flags)},
  };
}

// ---- the schedule ---------------------------------------------------------------------------

void CaptureDaemon::planNext(SteadyTime now, bool slot_taken) {
  const ScheduleConfig& schedule = config_.daemon.schedule;
  replan_at_.reset();
  state_.next_target_deg.reset();
  switch (schedule.mode) {
    case ScheduleMode::kInterval:
      // The first stack at once, then on the interval's grid; missed slots are not caught up.
      if (!next_scheduled_)
        next_scheduled_ = now;
      else if (slot_taken)
        *next_scheduled_ += schedule.interval;
      if (*next_scheduled_ < now) next_scheduled_ = now + schedule.interval;
      if (!slot_taken) next_scheduled_ = std::min(*next_scheduled_, now + schedule.interval);
      break;
    case ScheduleMode::kAlphaTargets:
      planAlphaTargets(clock_.utcNow());
      break;
    case ScheduleMode::kButton:
      next_scheduled_.reset();
      break;
  }

  state_.next_capture_time.reset();
  if (next_scheduled_)
    state_.next_capture_time =
        clock_.utcNow() +
        std::chrono::duration_cast<std::chrono::microseconds>(*next_scheduled_ - now);
}

std::optional<sun::ModuleOrientation> CaptureDaemon::plannedModule() {
  if (last_geometry_) return last_geometry_->module;
  if (!sensors_) return std::nullopt;
  const auto measured = sensors_->measureWithClock(clock_.utcNow(), clock_.clockStatus());
  if (!measured) {
    spdlog::warn("glarecamd: α targets: {}", measured.error().message);
    return std::nullopt;
  }
  last_geometry_ = *measured;
  return measured->module;
}

void CaptureDaemon::planAlphaTargets(UtcTime from) {
  next_scheduled_.reset();
  planned_crossing_.reset();
  const std::optional<sun::ModuleOrientation> module = plannedModule();
  const auto retry = [this](std::string why) {
    replan_at_ = clock_.now() + std::chrono::hours(1);
    state_.skip_reason = std::move(why);
  };
  if (!config_.rig.site || !module) return retry("α targets need the module's tilt");
  const auto crossings = alphaCrossings(*config_.rig.site, *module, from, kAlphaPlanHorizon,
                                        config_.daemon.schedule.alpha_targets_deg);
  if (!crossings) return retry(crossings.error().message);
  for (const AlphaCrossing& crossing : *crossings) {
    const auto taken = taken_targets_.find(crossing.target_deg);
    if (taken != taken_targets_.end() && crossing.time - taken->second < kAlphaTargetRepeatGuard)
      continue;
    next_scheduled_ = clock_.steadyAt(crossing.time);
    planned_crossing_ = crossing.time;
    state_.next_target_deg = crossing.target_deg;
    return;
  }
  retry("no α target is crossed in the next 24 h");
}

bool CaptureDaemon::mayCapture() const {
  const bool enough = options_.max_stacks && state_.stacks_captured >= *options_.max_stacks;
  return state_.ready && camera_.camera() && !stopping_ && !enough;
}

bool CaptureDaemon::scheduledDue(SteadyTime now) const {
  return next_scheduled_ && now >= *next_scheduled_;
}

SteadyTime CaptureDaemon::nextDeadline(SteadyTime now) const {
  SteadyTime deadline = next_disk_check_;
  const auto earliest = [&deadline](const std::optional<SteadyTime>& t) {
    if (t) deadline = std::min(deadline, *t);
  };
  if (watchdog_interval_) earliest(next_watchdog_);
  // Only a capture that can be taken wakes the loop: a due one that cannot would spin it.
  if (mayCapture()) earliest(next_scheduled_);
  if (mayCapture() && !requests_.empty()) earliest(now);
  if (!camera_.camera()) earliest(camera_.retryAt().value_or(now));
  earliest(replan_at_);
  earliest(inclinometer_retry_at_);
  return std::max(deadline, now);
}

// ---- events ---------------------------------------------------------------------------------

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
      if (io_) state_.gpio_fault.clear();  // the button reads again
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
  if (event.error && event.stage == WorkerEvent::Stage::kWritten && !event.last) {
    // Kept by the worker: capture pauses until the disk takes a write again.
    state_.disk_fault =
        fmt::format("{}{}; it is kept until the disk takes it", kWriteFailed, event.error->message);
    spdlog::error("glarecamd: {}: {}", event.stack_id, state_.disk_fault);
  } else if (event.error) {
    ++state_.stacks_failed;
    state_.worker_fault = event.error->message;
    spdlog::error("glarecamd: {}: {}", event.stack_id, event.error->message);
  } else {
    switch (event.stage) {
      case WorkerEvent::Stage::kWritten:
        ++state_.stacks_written;
        if (state_.disk_fault.starts_with(kWriteFailed) && !worker_->hasParked()) {
          spdlog::info("glarecamd: disk: the kept stacks are written; capture resumes");
          state_.disk_fault.clear();
        }
        spdlog::info("glarecamd: wrote {}", event.path.string());
        break;
      case WorkerEvent::Stage::kProcessed:
        ++state_.stacks_processed;
        spdlog::info("glarecamd: processed {}", event.detail);
        break;
      case WorkerEvent::Stage::kPublished:
        state_.day = fmt::format("{}: {}", event.path.filename().string(), event.detail);
        spdlog::info("glarecamd: day {}", state_.day);
        break;
    }
    if (event.stage != WorkerEvent::Stage::kWritten) state_.worker_fault.clear();
  }
  if (event.last && event.captured && options_.max_stacks &&
      ++stacks_done_ >= *options_.max_stacks && !stopping_) {
    spdlog::info("glarecamd: {} stacks done: stopping", stacks_done_);
    stopping_ = true;
  }
}

void CaptureDaemon::checkDisk(SteadyTime now) {
  next_disk_check_ = now + kDiskCheckPeriod;
  const fs::path& root = config_.daemon.output.root;
  const auto state = services_.disk->probe(root);
  std::string reason = state ? diskPauseReason(*state, config_.daemon.output.reserve_bytes, root)
                             : state.error().message;
  const bool kept = worker_ && worker_->hasParked();
  if (kept && reason.empty()) {
    // statvfs cannot see every refusal: a probe write first, then the kept stacks. The fault
    // ends when they are written (handleWorker).
    if (outputWritable()) worker_->retryParked();
    return;
  }
  if (reason.empty() && state_.disk_fault.starts_with(kWriteFailed)) return;  // being retried
  if (reason.empty() && !state_.disk_fault.empty() && !outputWritable()) reason = state_.disk_fault;
  if (reason == state_.disk_fault) return;
  if (reason.empty())
    spdlog::info("glarecamd: disk: {} free; capture resumes", formatBytes(state->free_bytes));
  else
    spdlog::error("glarecamd: disk: {}; capture pauses", reason);
  state_.disk_fault = std::move(reason);
}

// The planned crossing's steady time, as the wall clock now maps it: a wall clock that jumped
// (NTP's first synchronisation on a board without a clock) moved it.
void CaptureDaemon::checkWallClock(SteadyTime now) {
  if (!planned_crossing_ || !next_scheduled_) return;
  const auto moved = clock_.steadyAt(*planned_crossing_) - *next_scheduled_;
  if (std::chrono::abs(moved) < kWallClockJump) return;
  spdlog::warn("glarecamd: the wall clock jumped by {:.0f} s; the α targets are planned again",
               -std::chrono::duration<double>(moved).count());
  planNext(now, false);
}

void CaptureDaemon::retryInclinometer() {
  inclinometer_retry_at_.reset();
  capture::CaptureSettings unused;
  bool pause = false;
  measureGeometry(unused, pause);  // clears the fault when it reads, else sets the next retry
}

void CaptureDaemon::checkClock() {
  if (!config_.rig.site) return;  // only the sun's position needs the wall clock
  const sun::ClockStatus clock = clock_.clockStatus();
  std::string warning =
      clock.synchronised ? std::string()
                         : fmt::format("not synchronised ({}); stacks are flagged", clock.detail);
  if (warning != state_.clock_warning && !warning.empty())
    spdlog::warn("glarecamd: clock {}", warning);
  state_.clock_warning = std::move(warning);
}

void CaptureDaemon::feedWatchdog(SteadyTime now) {
  if (!watchdog_interval_ || now < next_watchdog_) return;
  next_watchdog_ = now + *watchdog_interval_ / 2;
  if (!healthy(now)) return;  // a stuck worker: systemd's watchdog will restart us
  services_.notifier->notify("WATCHDOG=1");
  ++state_.watchdog_pings;
}

bool CaptureDaemon::healthy(SteadyTime now) const {
  const auto busy = worker_ ? worker_->busySince() : std::nullopt;
  return !busy || now - *busy < kWorkerStallLimit;
}

void CaptureDaemon::publishStatus() {
  state_.led = ledState(state_, state_.capturing);
  if (led_) led_->setStatus(state_.led);
  std::string line = statusLine(state_, scheduleText(config_.daemon.schedule));
  if (line == state_.status) return;
  state_.status = std::move(line);
  services_.notifier->notify("STATUS=" + state_.status);
  spdlog::debug("glarecamd: status: {}", state_.status);
}

}  // namespace glarecam::daemon
