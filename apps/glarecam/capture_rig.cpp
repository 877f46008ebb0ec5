#include "apps/glarecam/capture_rig.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>

#include "apps/glarecam/interruption.h"
#include "apps/glarecam/sample_progress.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "core/time.h"
#include "daemon/daemon_config.h"
#include "daemon/rig_stack.h"
#include "rig/gpio/rig_io_registry.h"

namespace glarecam::apps {

Result<std::unique_ptr<CaptureRig>> CaptureRig::open(const std::string& config_path,
                                                     bool alpha_given, bool on_button,
                                                     bool show_progress) {
  std::unique_ptr<CaptureRig> rig(new CaptureRig);
  rig->show_progress_ = show_progress;
  GLARECAM_ASSIGN(rig->config_, daemon::readRigConfig(config_path));
  const rig::RigConfig& config = rig->config_;
  if (config.inclinometer && !config.site && !config.fixed_source)
    spdlog::warn(
        "capture: {} has an [inclinometer] but neither [site] nor [source]: α is not "
        "measured",
        config_path);
  if (config.site || config.fixed_source) {
    if (alpha_given)
      return badInput(fmt::format("capture: --alpha contradicts {}, whose [{}] gives α; give one",
                                  config_path, config.site ? "site" : "source"));
    GLARECAM_ASSIGN(rig->sensors_, rig::RigSensors::open(config));
  }
  if (on_button && !(config.gpio && config.gpio->button))
    return badInput(
        fmt::format("capture: --on-button, but {} has no [gpio] button line", config_path));
  if (config.gpio) {
    GLARECAM_ASSIGN(rig->io_, rig::openRigIo(*config.gpio));
    spdlog::info("capture: GPIO {}", rig->io_->description());
    rig->led_ = std::make_unique<rig::StatusLed>(*rig->io_);
    rig->led_->start();
  }
  rig->on_button_ = on_button;
  return rig;
}

CaptureRig::~CaptureRig() {
  if (led_) {
    const Status stopped = led_->stop();  // the LED dark: glarecam no longer drives it
    if (!stopped) spdlog::warn("capture: {}", stopped.error().message);
  }
}

Result<std::optional<Calibration>> CaptureRig::cameraCalibration() const {
  return rig::rigCameraCalibration(config_);
}

Status CaptureRig::measureInto(capture::CaptureSettings& settings) {
  rig::RigGeometry geometry;
  const UtcTime now = utcNow();
  GLARECAM_ASSIGN(geometry,
                  withSampleProgress(config_.inclinometer ? config_.inclinometer->tilt.samples : 0,
                                     show_progress_ && config_.inclinometer.has_value(),
                                     [&](const std::function<void()>& on_sample) {
                                       return sensors_->measure(now, on_sample);
                                     }));
  for (const std::string& warning : geometry.warnings) spdlog::warn("capture: {}", warning);
  spdlog::info("capture: α {:.3f}° ± {:.3f}° (module tilt {:.3f}°)", geometry.alpha_deg,
               geometry.alpha_uncertainty_deg, geometry.module.tilt_deg);
  settings.alpha_deg = geometry.alpha_deg;
  settings.geometry = rig::geometryJson(geometry);
  measured_ = std::move(geometry);
  return {};
}

void CaptureRig::finishStack(capture::CapturedStack& stack, UtcTime bracket_start,
                             UtcTime bracket_end) {
  if (!measured_ || !measured_->sun) return;  // a fixed source does not move
  const Status recorded =
      daemon::recordBracketGeometry(*sensors_, *measured_, stack, bracket_start, bracket_end);
  // On failure the stack keeps α from before the bracket.
  if (!recorded) spdlog::warn("capture: α for the bracket's middle: {}", recorded.error().message);
}

Result<bool> CaptureRig::waitForButton() {
  if (!on_button_) return true;
  std::fprintf(stderr, "capture: waiting for the button\n");
  return waitForButtonPress(*io_, config_.gpio->debounce, rig::RigClock::time_point::max());
}

void CaptureRig::showCapturing(bool capturing) {
  if (led_) led_->setStatus(capturing ? rig::RigState::capturing() : rig::RigState::ready());
}

void CaptureRig::showFault(rig::FaultCode fault) {
  if (led_) led_->setStatus(rig::RigState::faulted(fault));
}

}  // namespace glarecam::apps
