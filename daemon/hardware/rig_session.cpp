#include "daemon/hardware/rig_session.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <condition_variable>
#include <cstdio>
#include <mutex>

#include "daemon/hardware/simulated_rig.h"
#include "rig/gpio/button_debouncer.h"
#include "rig/gpio/rig_io_registry.h"
#include "sun/clear_sky.h"

namespace glarecam::daemon {

Status checkPlausibleTilt(const rig::RigGeometry& geometry, const FaultConfig& faults) {
  if (!geometry.tilt) return {};  // a fixed tilt from the config
  const double tilt_deg = geometry.tilt->module_tilt_deg;
  if (tilt_deg >= faults.min_tilt_deg && tilt_deg <= faults.max_tilt_deg) return {};
  return hardwareError(fmt::format(
      "{}: implausible tilt {:.2f}° (outside [{:g}, {:g}]°: a loose sensor, a moved rig?)",
      geometry.inclinometer_uri, tilt_deg, faults.min_tilt_deg, faults.max_tilt_deg));
}

RigSession::RigSession(rig::RigConfig config, RigSessionOptions options)
    : config_(std::move(config)), options_(std::move(options)) {
  if (!options_.open_rig_io) options_.open_rig_io = rig::openRigIo;
}

RigSession::~RigSession() {
  closeGpio();
  illuminance_sampler_.reset();  // stops a sampling still running, before its instrument goes
}

Status RigSession::openIlluminance() {
  if (!config_.illuminance) return {};
  auto opened = rig::openIlluminance(*config_.illuminance);
  if (!opened)
    return std::unexpected(withContext(opened.error(), config_.path.string() + ": [illuminance]"));
  illuminance_ = std::move(*opened);
  illuminance_sampler_ = std::make_unique<rig::IlluminanceSampler>(
      *illuminance_.instrument, config_.illuminance->sample_interval);
  spdlog::info("{}: the source illuminance from {}", options_.log_name,
               illuminance_.instrument->info().description);
  return {};
}

Status RigSession::openSensors() {
  sensors_.reset();
  last_geometry_.reset();  // the module may have moved, or the config's geometry changed
  logged_warnings_.clear();
  if (!measuresAlpha()) return {};
  GLARECAM_ASSIGN(sensors_, rig::RigSensors::open(config_));
  return {};
}

Result<rig::RigGeometry> RigSession::read(UtcTime time,
                                          const std::optional<sun::ClockStatus>& clock) {
  const std::optional<sun::ClockStatus> rig_clock =
      clock ? std::optional(rigClockStatus(config_, *clock)) : std::nullopt;
  return sensors_->measureShowingProgress(time, rig_clock, options_.show_progress);
}

Result<rig::RigGeometry> RigSession::measure(UtcTime time,
                                             const std::optional<sun::ClockStatus>& clock) {
  if (!sensors_) GLARECAM_CHECK(openSensors());  // a sensor absent before may have come back
  if (!sensors_) return badInput(config_.path.string() + ": the config gives no α");
  rig::RigGeometry geometry;
  GLARECAM_ASSIGN(geometry, read(time, clock));
  GLARECAM_CHECK(checkPlausibleTilt(geometry, options_.faults));
  for (const std::string& warning : geometry.warnings)
    if (logged_warnings_.insert(warning).second) spdlog::warn("{}: {}", options_.log_name, warning);
  last_geometry_ = geometry;
  return geometry;
}

std::optional<double> RigSession::sceneAlphaDeg() const {
  if (!last_geometry_) return std::nullopt;
  return last_geometry_->alpha_deg;
}

capture::SceneState RigSession::sceneState() const {
  capture::SceneState state{.alpha_deg = sceneAlphaDeg()};
  if (config_.fixed_source_illuminance) {
    state.source_illuminance_lx = config_.fixed_source_illuminance->illuminance_lx;
  } else if (last_geometry_ && last_geometry_->sun && config_.site) {
    if (const auto sky = sun::clearSkySource(last_geometry_->time, *config_.site))
      state.source_illuminance_lx = sky->illuminance_lx;
  }
  return state;
}

void RigSession::record(const Result<rig::RigGeometry>& measured,
                        capture::CaptureSettings& settings) {
  if (!measured) {
    settings.geometry = nlohmann::json{{"alpha_unknown", measured.error().message}};
    return;
  }
  settings.alpha_deg = measured->alpha_deg;
  settings.geometry = rig::geometryJson(*measured);
}

void RigSession::recordBracketMiddle(capture::CapturedStack& stack,
                                     const rig::RigGeometry& geometry, UtcTime bracket_start,
                                     UtcTime bracket_end) const {
  if (!geometry.sun) {  // a fixed source does not move
    capture::recordAlpha(stack, geometry.alpha_deg, rig::geometryJson(geometry));
    return;
  }
  const auto retimed =
      sensors_->retime(geometry, bracket_start + (bracket_end - bracket_start) / 2);
  if (!retimed) {  // the stack keeps α from before the bracket
    spdlog::warn("{}: α for the bracket's middle: {}", options_.log_name, retimed.error().message);
    return;
  }
  capture::recordAlpha(stack, retimed->alpha_deg, rig::geometryJson(*retimed));
}

Status RigSession::openGpio() {
  closeGpio();
  if (!config_.gpio) return {};
  GLARECAM_ASSIGN(io_, options_.open_rig_io(*config_.gpio));
  spdlog::info("{}: GPIO {}", options_.log_name, io_->description());
  led_ = std::make_unique<rig::StatusLed>(*io_);
  led_->start();
  return {};
}

void RigSession::watchButton(std::function<void()> on_press,
                             std::function<void(const Error&)> on_error) {
  if (!io_ || !io_->hasButton()) return;
  button_thread_ = std::jthread([io = io_.get(), debounce = config_.gpio->debounce,
                                 on_press = std::move(on_press),
                                 on_error = std::move(on_error)](std::stop_token stop) {
    rig::ButtonWatcher watcher(*io, debounce);
    std::mutex mutex;
    std::condition_variable_any pause;
    while (!stop.stop_requested()) {
      const auto pressed = watcher.waitForPress(rig::RigClock::time_point::max(), stop);
      if (pressed && *pressed) on_press();
      if (pressed) continue;
      on_error(pressed.error());
      std::unique_lock lock(mutex);
      pause.wait_for(lock, stop, kButtonRetry, [] { return false; });
    }
  });
}

void RigSession::closeGpio() {
  if (button_thread_.joinable()) {
    button_thread_.request_stop();
    button_thread_.join();
  }
  if (led_) {
    const Status stopped = led_->stop();  // the LED dark: glarecam no longer drives it
    if (!stopped) spdlog::warn("{}: {}", options_.log_name, stopped.error().message);
  }
  led_.reset();
  io_.reset();
}

void RigSession::show(rig::RigState state) {
  if (led_) led_->setStatus(state);
}

Result<std::optional<Calibration>> RigSession::cameraCalibration() const {
  return rig::rigCameraCalibration(config_);
}

Result<bool> RigSession::prepareStack(capture::CaptureSettings& settings, std::uint64_t index) {
  for (;;) {
    if (options_.on_button) {
      std::fprintf(stderr, "capture: waiting for the button\n");
      bool pressed = false;
      GLARECAM_ASSIGN(pressed, rig::waitForButtonPress(*io_, config_.gpio->debounce,
                                                       rig::RigClock::time_point::max()));
      if (!pressed) return false;
    }
    if (!measuresAlpha() || (index == 0 && !options_.on_button && last_geometry_)) break;
    const auto measured = measure(utcNow(), sun::systemClockStatus());
    if (measured) {
      spdlog::info("capture: α {:.3f}° ± {:.3f}° (module tilt {:.3f}°)", measured->alpha_deg,
                   measured->alpha_uncertainty_deg, measured->module.tilt_deg);
      record(measured, settings);
      break;
    }
    if (!options_.on_button || measured.error().code != ErrorCode::kHardware)
      return std::unexpected(measured.error());
    spdlog::error("capture: {}; press the button to try again", measured.error().message);
    show(rig::RigState::faulted(rig::FaultCode::kInclinometer));
  }
  show(rig::RigState::capturing());
  // The bracket follows at once: its source illuminance is sampled from now to finishStack().
  // A source given for the series (--source-illuminance) is the operator's word: kept.
  sampling_ = illuminance_sampler_ && !settings.source_illuminance;
  if (illuminance_sampler_ && settings.source_illuminance && index == 0)
    spdlog::info("{}: the given source illuminance is recorded; [illuminance] is not read",
                 options_.log_name);
  if (sampling_ && config_.site) {  // a simulated instrument serves the clear-sky sun of now
    const auto lx = simulatedSourceIlluminance(utcNow(), *config_.site);
    rig::setSimulatedIlluminance(illuminance_, lx ? *lx : 0.0);
  }
  if (sampling_) illuminance_sampler_->start();
  return true;
}

void RigSession::finishStack(capture::CapturedStack& stack, UtcTime bracket_start,
                             UtcTime bracket_end) {
  show(rig::RigState::ready());
  if (sampling_) {
    sampling_ = false;
    auto source = illuminance_sampler_->stop();
    if (source)
      stack.manifest.source_illuminance = *source;
    else
      spdlog::warn("{}: illuminance: {}; the stack is unreferred", options_.log_name,
                   source.error().message);
  }
  if (last_geometry_ && last_geometry_->sun)
    recordBracketMiddle(stack, *last_geometry_, bracket_start, bracket_end);
}

}  // namespace glarecam::daemon
