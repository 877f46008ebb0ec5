#include "rig/gpio/sim_rig_io.h"

#include <spdlog/spdlog.h>

#include <utility>

namespace glarecam::rig {

SimRigIo::SimRigIo(const RigIoConfig& config, RigClockFunction clock)
    : clock_(std::move(clock)),
      has_trigger_(config.trigger.has_value()),
      has_led_(config.led.has_value()),
      has_button_(config.button.has_value()),
      trigger_pulse_(config.trigger_pulse) {
  std::string lines;
  for (const auto& [line, role] :
       {std::pair{&config.trigger, "trigger"}, std::pair{&config.led, "LED"},
        std::pair{&config.button, "button"}}) {
    if (!*line) continue;
    if (!lines.empty()) lines += ", ";
    lines += std::string(role) + " " + describeGpioLine(**line);
  }
  description_ = "simulated chip " + config.chip + ": " + (lines.empty() ? "no lines" : lines);
}

Status SimRigIo::setLed(bool on) {
  std::lock_guard lock(mutex_);
  if (failure_) return std::unexpected(*failure_);
  if (!has_led_ || on == led_on_) return {};
  led_on_ = on;
  led_changes_.push_back({clock_(), on});
  spdlog::debug("simulated GPIO: LED {}", on ? "on" : "off");
  return {};
}

Status SimRigIo::pulseTrigger() {
  std::lock_guard lock(mutex_);
  if (failure_) return std::unexpected(*failure_);
  if (!has_trigger_) return {};
  trigger_pulses_.push_back({clock_(), trigger_pulse_});
  spdlog::info("simulated GPIO: trigger pulse of {} µs", trigger_pulse_.count());
  return {};
}

Result<bool> SimRigIo::buttonPressed() {
  std::lock_guard lock(mutex_);
  ++button_reads_;
  if (failure_) return std::unexpected(*failure_);
  if (!has_button_) return false;
  const RigClock::time_point now = clock_();
  bool pressed = false;
  for (const ButtonStep& step : button_script_) {
    if (step.at > now) break;
    pressed = step.pressed;
  }
  return pressed;
}

void SimRigIo::setButtonPressed(bool pressed) {
  std::lock_guard lock(mutex_);
  button_script_ = {{RigClock::time_point::min(), pressed}};
}

void SimRigIo::scriptButton(std::vector<ButtonStep> steps) {
  std::lock_guard lock(mutex_);
  button_script_ = std::move(steps);
}

void SimRigIo::failWith(std::optional<Error> error) {
  std::lock_guard lock(mutex_);
  failure_ = std::move(error);
}

bool SimRigIo::ledOn() const {
  std::lock_guard lock(mutex_);
  return led_on_;
}

std::vector<SimRigIo::LedChange> SimRigIo::ledChanges() const {
  std::lock_guard lock(mutex_);
  return led_changes_;
}

std::vector<SimRigIo::TriggerPulse> SimRigIo::triggerPulses() const {
  std::lock_guard lock(mutex_);
  return trigger_pulses_;
}

int SimRigIo::buttonReads() const {
  std::lock_guard lock(mutex_);
  return button_reads_;
}

}  // namespace glarecam::rig
