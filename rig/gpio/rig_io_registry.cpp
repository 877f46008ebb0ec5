#include "rig/gpio/rig_io_registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "core/uri_parameters.h"
#include "rig/gpio/sim_rig_io.h"

namespace glarecam::rig {

namespace {

constexpr std::string_view kSimChip = "sim";
constexpr std::string_view kUriName = "GPIO chip sim:";
// The simulated operator holds the button this long per press, or twice the debounce if longer.
constexpr std::chrono::milliseconds kSimPressLength{100};
constexpr int kSimScriptedPresses = 10000;    // hours of presses at any sensible period
constexpr double kMinSimButtonPeriodS = 0.5;  // a press and a release must both debounce

Result<double> parseButtonPeriod(std::string_view parameters) {
  double period_s = 0;
  GLARECAM_CHECK(forEachUriParameter(
      parameters, kUriName, [&](std::string_view key, std::string_view value) -> Status {
        if (key != "button_period_s")
          return badInput(
              fmt::format("{} unknown key '{}' (known: button_period_s)", kUriName, key));
        GLARECAM_ASSIGN(period_s, parseUriNumber(value, key, kUriName));
        if (!(period_s >= kMinSimButtonPeriodS && period_s <= 86400))
          return badInput(fmt::format("{} button_period_s={} must be in [{}, 86400]", kUriName,
                                      value, kMinSimButtonPeriodS));
        return {};
      }));
  return period_s;
}

// The simulated chip has a Raspberry Pi 4's lines (gpiochip0, pinctrl-bcm2711: 58 lines named
// GPIO0..GPIO57), so that a config's lines are checked as on the rig.
constexpr unsigned kSimChipLines = 58;
constexpr std::string_view kSimLinePrefix = "GPIO";

Result<unsigned> simLineOffset(const GpioLine& line, std::string_view role) {
  if (const unsigned* offset = std::get_if<unsigned>(&line.line)) {
    if (*offset < kSimChipLines) return *offset;
    return hardwareError(fmt::format("line {} ({}) is beyond the simulated chip's {} lines (0..{})",
                                     *offset, role, kSimChipLines, kSimChipLines - 1));
  }
  const std::string_view name = std::get<std::string>(line.line);
  unsigned number = 0;
  if (name.starts_with(kSimLinePrefix) && name.size() > kSimLinePrefix.size()) {
    const std::string_view digits = name.substr(kSimLinePrefix.size());
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
    const bool leading_zero = digits.size() > 1 && digits.front() == '0';  // no line "GPIO022"
    if (error == std::errc() && end == digits.data() + digits.size() && !leading_zero &&
        number < kSimChipLines)
      return number;
  }
  return hardwareError(
      fmt::format("line '{}' ({}) not found on the simulated chip (its lines: GPIO0..GPIO{})", name,
                  role, kSimChipLines - 1));
}

// Each configured line exists on the simulated chip, and no line serves two roles.
Status checkSimLines(const RigIoConfig& config) {
  std::vector<std::pair<unsigned, std::string_view>> used;
  for (const auto& [line, role] :
       {std::pair{&config.trigger, "trigger"}, std::pair{&config.led, "LED"},
        std::pair{&config.button, "button"}}) {
    if (!*line) continue;
    unsigned offset = 0;
    GLARECAM_ASSIGN(offset, simLineOffset(**line, role));
    for (const auto& [other, other_role] : used) {
      if (other == offset)
        return badInput(fmt::format("GPIO {} and {} are the same line {} of the simulated chip",
                                    other_role, role, offset));
    }
    used.emplace_back(offset, role);
  }
  return {};
}

Result<std::unique_ptr<RigIo>> openSimRigIo(const RigIoConfig& config,
                                            std::string_view parameters) {
  GLARECAM_CHECK(checkSimLines(config));
  double period_s = 0;
  GLARECAM_ASSIGN(period_s, parseButtonPeriod(parameters));
  auto io = std::make_unique<SimRigIo>(config);
  if (period_s > 0) {
    const auto period =
        std::chrono::duration_cast<RigClock::duration>(std::chrono::duration<double>(period_s));
    // A press, and the release after it, must each outlast the debounce (twice, for margin).
    const auto press = std::max<RigClock::duration>(kSimPressLength, 2 * config.debounce);
    if (period < 2 * press)
      return badInput(
          fmt::format("{} button_period_s={:g} is too short for debounce_ms = {}: "
                      "at least {:g} s",
                      kUriName, period_s, config.debounce.count(),
                      2 * std::chrono::duration<double>(press).count()));
    std::vector<SimRigIo::ButtonStep> steps;
    const RigClock::time_point start = RigClock::now();
    for (int k = 1; k <= kSimScriptedPresses; ++k) {
      steps.push_back({start + k * period, true});
      steps.push_back({start + k * period + press, false});
    }
    io->scriptButton(std::move(steps));
  }
  return io;
}

}  // namespace

Result<std::unique_ptr<RigIo>> openRigIo(const RigIoConfig& config) {
  GLARECAM_CHECK(config.validate());
  const std::string_view chip = config.chip;
  if (chip == kSimChip) return openSimRigIo(config, {});
  if (chip.starts_with("sim:")) return openSimRigIo(config, chip.substr(kSimChip.size() + 1));
  return openGpiodRigIo(config);
}

}  // namespace glarecam::rig
