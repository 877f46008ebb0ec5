#include "rig/gpio/rig_io.h"

#include <array>
#include <utility>

#include "core/build_config.h"

namespace glarecam::rig {
namespace {

struct NamedLine {
  std::string_view role;
  const std::optional<GpioLine>* line;
};

bool sameLine(const GpioLine& a, const GpioLine& b) { return a.line == b.line; }

}  // namespace

std::string describeGpioLine(const GpioLine& line) {
  std::string text = "line ";
  if (const auto* offset = std::get_if<unsigned>(&line.line)) {
    text += std::to_string(*offset);
  } else {
    text += "'" + std::get<std::string>(line.line) + "'";
  }
  if (line.active_low) text += ", active-low";
  return text;
}

Status RigIoConfig::validate() const {
  if (chip.empty()) return badInput("GPIO chip: empty (a name such as gpiochip0, a path or label)");
  const std::array<NamedLine, 3> lines{{{"trigger", &trigger}, {"LED", &led}, {"button", &button}}};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!*lines[i].line) continue;
    const GpioLine& line = **lines[i].line;
    if (const auto* name = std::get_if<std::string>(&line.line); name && name->empty()) {
      return badInput(std::string("GPIO ") + std::string(lines[i].role) +
                      " line: empty name (give an offset or a name from gpioinfo)");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (*lines[j].line && sameLine(**lines[j].line, line)) {
        return badInput("GPIO " + std::string(lines[j].role) + " and " +
                        std::string(lines[i].role) + " are the same " + describeGpioLine(line));
      }
    }
  }
  // The pull-up holds an idle button line high: unless that level counts as released
  // (active-low), the button reads pressed for ever and no press is ever seen.
  if (button && button_pull_up && !button->active_low) {
    return badInput(
        "GPIO button: the pull-up holds the line high at rest, so a button to ground is "
        "active-low (button_active_low = true); for a button to 3.3 V with an external "
        "pull-down set button_pull_up = false");
  }
  if (debounce < std::chrono::milliseconds::zero() || debounce > kMaxDebounce) {
    return badInput("GPIO button debounce " + std::to_string(debounce.count()) +
                    " ms: outside 0.." + std::to_string(kMaxDebounce.count()) + " ms");
  }
  if (trigger_pulse <= std::chrono::microseconds::zero() || trigger_pulse > kMaxTriggerPulse) {
    return badInput("GPIO trigger pulse " + std::to_string(trigger_pulse.count()) +
                    " us: outside 1.." + std::to_string(kMaxTriggerPulse.count()) + " us");
  }
  return {};
}

#if !GLARECAM_WITH_GPIOD
Result<std::unique_ptr<RigIo>> openGpiodRigIo(const RigIoConfig& config) {
  GLARECAM_CHECK(config.validate());
  return hardwareError("GPIO chip " + config.chip +
                       ": glarecam was built without libgpiod (install libgpiod-dev and "
                       "reconfigure with -DGLARECAM_WITH_GPIOD=ON)");
}
#endif

}  // namespace glarecam::rig
