// The rig's GPIO: up to three lines on one GPIO chip. A trigger output pulses the camera's
// hardware trigger input, a status LED shows ready / capturing / fault (status_led.h), and an
// operator button asks for a capture (button_debouncer.h). Every line is optional: a rig without
// one simply lacks the feature.
//
// RigIo is the one interface at the hardware boundary. Its backends: the Linux GPIO character
// device through libgpiod (openGpiodRigIo(), built when GLARECAM_WITH_GPIOD) and a simulator
// (sim_rig_io.h). Everything above it (blink codes, debouncing) is pure and works on either.
//
// Levels are logical: `true` is "active" (LED lit, trigger asserted, button pressed) after the
// line's active_low inversion, never the electrical level. A line that is not configured is a
// no-op: setLed() and pulseTrigger() succeed and do nothing, buttonPressed() reads "not pressed";
// callers that care ask hasLed() / hasTrigger() / hasButton(). Implementations are thread-safe:
// the status LED is driven from its own thread while the capture pulses and polls.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "core/error.h"

namespace glarecam::rig {

// The clock of everything timed on the rig's I/O (blink codes, debouncing, the simulator's
// records), injectable so that tests run on a clock they advance themselves.
using RigClock = std::chrono::steady_clock;
using RigClockFunction = std::function<RigClock::time_point()>;

// The longest trigger pulse accepted: the call blocks for the pulse, and cameras' opto-isolated
// inputs need microseconds to a few milliseconds.
inline constexpr std::chrono::microseconds kMaxTriggerPulse{100'000};
// The longest debounce accepted: beyond this a press would feel lost.
inline constexpr std::chrono::milliseconds kMaxDebounce{1'000};

// One GPIO line of the chip: by offset (17) or by the name the device tree gives it
// ("GPIO17", "STATUS_LED"; `gpioinfo` lists both).
struct GpioLine {
  std::variant<unsigned, std::string> line;
  bool active_low = false;  // the line is active at the low electrical level
};

// "line 17", "line 'STATUS_LED'", with ", active-low" when inverted: for messages.
std::string describeGpioLine(const GpioLine& line);

struct RigIoConfig {
  // The GPIO chip: its name ("gpiochip0"), its /dev path ("/dev/gpiochip0"), its number ("0") or
  // its label ("pinctrl-bcm2711").
  std::string chip = "gpiochip0";
  std::optional<GpioLine> trigger;  // output, pulsed once per hardware-triggered frame
  std::optional<GpioLine> led;      // output, the status LED
  std::optional<GpioLine> button;   // input, the operator's capture button
  // The button line's internal pull-up (for a button wired to ground; then active_low = true).
  // Off when the board has an external pull-up or the kernel cannot bias lines (before 5.5).
  bool button_pull_up = true;
  std::chrono::milliseconds debounce{50};          // the button must be stable this long
  std::chrono::microseconds trigger_pulse{1'000};  // width of a trigger pulse

  // The first problem in words (kBadInput): an empty chip or line name, a line used twice,
  // a debounce outside [0, kMaxDebounce] or a trigger pulse outside (0, kMaxTriggerPulse].
  Status validate() const;
};

class RigIo {
 public:
  virtual ~RigIo() = default;
  RigIo(const RigIo&) = delete;
  RigIo& operator=(const RigIo&) = delete;

  // What was opened, for the log: "gpiochip0 [pinctrl-bcm2711]: trigger line 17, LED line 27,
  // button line 'BUTTON' (22, active-low, pull-up)".
  virtual const std::string& description() const = 0;

  virtual bool hasTrigger() const = 0;
  virtual bool hasLed() const = 0;
  virtual bool hasButton() const = 0;

  // Lights or darkens the status LED. kHardware error naming the line when the write fails.
  virtual Status setLed(bool on) = 0;
  // Asserts the trigger for the configured pulse width, then releases it; blocks for the pulse.
  // The line is left inactive even when the pulse failed half-way, if at all possible.
  virtual Status pulseTrigger() = 0;
  // The button's present level, undebounced (ButtonWatcher debounces): true while pressed.
  virtual Result<bool> buttonPressed() = 0;

 protected:
  RigIo() = default;
};

// Opens the configured lines of the chip for glarecam (consumer "glarecam"): outputs requested
// inactive, the button as an input. kBadInput when the config is invalid; kHardware naming the
// chip and line when the chip is absent or not a GPIO chip, a line is out of range or not found,
// busy (naming its user) or not accessible (with the gpio group / udev hint). When glarecam was
// built without libgpiod, always a kHardware error saying so. On destruction the outputs are
// driven inactive and every line is released.
Result<std::unique_ptr<RigIo>> openGpiodRigIo(const RigIoConfig& config);

}  // namespace glarecam::rig
