// A simulated rig GPIO for tests and `--simulate`: it records what glarecam does to the outputs
// (every LED level change and every trigger pulse, stamped by an injected clock) and reads the
// button from a level or a script the test sets (bounces included). Lines absent from the config
// are absent here too, with RigIo's no-op rules. It never sleeps: a trigger pulse is recorded
// with the configured width at once. Thread-safe, like every RigIo.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rig/gpio/rig_io.h"

namespace glarecam::rig {

class SimRigIo final : public RigIo {
 public:
  struct LedChange {
    RigClock::time_point at;
    bool on = false;
  };
  struct TriggerPulse {
    RigClock::time_point at;  // the rising edge
    std::chrono::microseconds width{0};
  };
  // From `at` on, the button reads `pressed` (until the next step).
  struct ButtonStep {
    RigClock::time_point at;
    bool pressed = false;
  };

  // The config is not validated here (openGpiodRigIo does that); only which lines exist, the
  // trigger pulse and the chip name are used. The LED starts dark, the button released.
  explicit SimRigIo(const RigIoConfig& config, RigClockFunction clock = RigClock::now);

  const std::string& description() const override { return description_; }
  bool hasTrigger() const override { return has_trigger_; }
  bool hasLed() const override { return has_led_; }
  bool hasButton() const override { return has_button_; }
  Status setLed(bool on) override;
  Status pulseTrigger() override;
  Result<bool> buttonPressed() override;

  // --- the test's side
  // A constant button level (replaces any script).
  void setButtonPressed(bool pressed);
  // The level at the clock's present time is that of the last step at or before it; before the
  // first step the button is released. Steps in time order.
  void scriptButton(std::vector<ButtonStep> steps);
  // Every later operation fails with this error (a line that died); nullopt heals it.
  void failWith(std::optional<Error> error);

  bool ledOn() const;
  std::vector<LedChange> ledChanges() const;  // level changes only, in order
  std::vector<TriggerPulse> triggerPulses() const;
  int buttonReads() const;  // how often buttonPressed() was called

 private:
  RigClockFunction clock_;
  std::string description_;
  bool has_trigger_ = false;
  bool has_led_ = false;
  bool has_button_ = false;
  std::chrono::microseconds trigger_pulse_;

  mutable std::mutex mutex_;
  bool led_on_ = false;
  std::vector<LedChange> led_changes_;
  std::vector<TriggerPulse> trigger_pulses_;
  std::vector<ButtonStep> button_script_;
  int button_reads_ = 0;
  std::optional<Error> failure_;
};

}  // namespace glarecam::rig
