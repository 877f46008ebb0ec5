// glarecam gpio: checks the rig's GPIO wiring, the LED, the trigger and the button
// (rig/gpio/wiring_check.h; docs/rig.md).
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/interruption.h"
#include "daemon/daemon_config.h"
#include "rig/gpio/rig_io_registry.h"
#include "rig/gpio/wiring_check.h"

namespace glarecam::apps {
namespace {

struct GpioArgs {
  std::string config = rig::kDefaultRigConfigPath;
  std::optional<std::string> led;
  double seconds = 5;
  std::optional<std::string> trigger;
  bool wait_button = false;
  double timeout_s = 30;
};

Status runGpio(const GpioArgs& args) {
  const double max_s = std::chrono::duration<double>(rig::kMaxWiringCheck).count();
  if (!(args.seconds > 0 && args.seconds <= max_s) ||
      !(args.timeout_s > 0 && args.timeout_s <= max_s))
    return badInput("gpio: --seconds and --timeout must be in (0, 3600]");
  std::optional<rig::RigState> led_state;
  if (args.led) GLARECAM_ASSIGN(led_state, rig::parseRigState(*args.led));
  std::uint64_t pulses = 0;
  if (args.trigger) {
    GLARECAM_ASSIGN(pulses, parseUnsigned(*args.trigger, "--trigger"));
    if (pulses < 1 || pulses > rig::kMaxTriggerPulses)
      return badInput("gpio: --trigger must be a count in [1, 10000]");
  }
  rig::RigConfig config;
  GLARECAM_ASSIGN(config, daemon::readRigConfig(args.config));
  if (!config.gpio) return badInput(args.config + ": no [gpio] section");
  std::unique_ptr<rig::RigIo> io;
  GLARECAM_ASSIGN(io, rig::openRigIo(*config.gpio));
  std::printf("%s\n", io->description().c_str());
  stopGracefullyOnSignals();  // Ctrl-C ends a pattern or a wait with the lines released
  if (led_state) {
    std::fprintf(stderr, "gpio: showing the LED pattern for %g s (Ctrl-C stops)\n", args.seconds);
    GLARECAM_CHECK(
        rig::showLedPattern(*io, *led_state, std::chrono::duration<double>(args.seconds)));
  }
  if (stopRequested()) return fail(ErrorCode::kInternal, "gpio: interrupted");
  if (pulses > 0) {
    GLARECAM_CHECK(rig::pulseTriggers(*io, pulses));
    std::printf("trigger: %llu pulse(s)\n", static_cast<unsigned long long>(pulses));
  }
  if (args.wait_button) {
    if (io->hasButton())
      std::fprintf(stderr, "gpio: press the button (waiting %g s)\n", args.timeout_s);
    bool pressed = false;
    GLARECAM_ASSIGN(pressed,
                    rig::waitForButtonWithin(*io, config.gpio->debounce,
                                             std::chrono::duration<double>(args.timeout_s)));
    if (stopRequested()) return fail(ErrorCode::kInternal, "gpio: interrupted");
    if (!pressed)
      return fail(ErrorCode::kHardware,
                  fmt::format("gpio: no button press within {:g} s", args.timeout_s));
    std::printf("button: pressed\n");
  }
  if (!led_state && pulses == 0 && !args.wait_button && io->hasButton()) {
    bool pressed = false;
    GLARECAM_ASSIGN(pressed, io->buttonPressed());
    std::printf("button: %s\n", pressed ? "pressed" : "released");
  }
  return {};
}

}  // namespace

void addGpioCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<GpioArgs>();
  CLI::App* sub = app.add_subcommand(
      "gpio",
      "Check the rig's GPIO wiring: show an LED pattern, pulse the trigger, wait for the button "
      "(the config's [gpio]; docs/rig.md)");
  sub->add_option("--config", args->config, "rig config (TOML)")->capture_default_str();
  sub->add_option("--led", args->led,
                  "show a status: ready, capturing, fault-camera, fault-inclinometer, fault-disk, "
                  "fault-clock");
  sub->add_option("--seconds", args->seconds, "how long --led shows it")->capture_default_str();
  sub->add_option("--trigger", args->trigger, "pulse the trigger line this many times (10 Hz)");
  sub->add_flag("--wait-button", args->wait_button, "wait for a debounced button press");
  sub->add_option("--timeout", args->timeout_s, "seconds --wait-button waits (exit 1 after)")
      ->capture_default_str();
  sub->callback([args, &action] { action = [args] { return runGpio(*args); }; });
}

}  // namespace glarecam::apps
