#include "rig/gpio/wiring_check.h"

#include <fmt/format.h>

#include <string>
#include <thread>

#include "core/interruption.h"
#include "rig/gpio/button_debouncer.h"

namespace glarecam::rig {

Result<RigState> parseRigState(std::string_view name) {
  if (name == "ready") return RigState::ready();
  if (name == "capturing") return RigState::capturing();
  for (const auto code :
       {FaultCode::kCamera, FaultCode::kInclinometer, FaultCode::kDisk, FaultCode::kClock}) {
    if (name == "fault-" + std::string(faultName(code))) return RigState::faulted(code);
  }
  return badInput(
      fmt::format("gpio: --led {} is unknown (known: ready, capturing, fault-camera, "
                  "fault-inclinometer, fault-disk, fault-clock)",
                  name));
}

Status showLedPattern(RigIo& io, RigState state, std::chrono::duration<double> duration) {
  if (!io.hasLed()) return badInput("gpio: --led, but the config's [gpio] has no led line");
  StatusLed led(io);
  led.setStatus(state);
  led.start();
  sleepUntil(std::chrono::steady_clock::now() +
             std::chrono::duration_cast<std::chrono::steady_clock::duration>(duration));
  GLARECAM_CHECK(led.stop());
  if (auto error = led.lastError()) return std::unexpected(*error);
  return {};
}

Status pulseTriggers(RigIo& io, std::uint64_t count) {
  if (!io.hasTrigger())
    return badInput("gpio: --trigger, but the config's [gpio] has no trigger line");
  for (std::uint64_t i = 0; i < count; ++i) {
    if (i > 0) std::this_thread::sleep_for(kTriggerSpacing);
    GLARECAM_CHECK(io.pulseTrigger());
  }
  return {};
}

Result<bool> waitForButtonWithin(RigIo& io, std::chrono::milliseconds debounce,
                                 std::chrono::duration<double> timeout) {
  if (!io.hasButton())
    return badInput("gpio: --wait-button, but the config's [gpio] has no button line");
  const auto deadline = RigClock::now() + std::chrono::duration_cast<RigClock::duration>(timeout);
  return waitForButtonPress(io, debounce, deadline);
}

}  // namespace glarecam::rig
