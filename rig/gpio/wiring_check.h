// `glarecam gpio`: checking the rig's wiring before it runs unattended. Each check drives one line
// of the rig's GPIO (rig_io.h) the way glarecamd will: an LED status pattern for a while, trigger
// pulses at a rate a scope can see, a wait for a debounced button press. Ctrl-C ends a pattern or
// a wait early with the lines released (core/interruption.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "rig/gpio/rig_io.h"
#include "rig/gpio/status_led.h"

namespace glarecam::rig {

// The longest a wiring check runs: a check, not a service.
inline constexpr std::chrono::seconds kMaxWiringCheck{3600};
inline constexpr std::uint64_t kMaxTriggerPulses = 10000;
// Between trigger pulses: 10 Hz, visible on a scope.
inline constexpr std::chrono::milliseconds kTriggerSpacing{100};

// "ready", "capturing" or "fault-<name>" (faultName): the status a name shows. kBadInput naming
// the known ones otherwise.
Result<RigState> parseRigState(std::string_view name);

// Shows `state` on the LED for `duration` (or until a stop is requested). kBadInput when the rig
// has no LED line; the LED's write error.
Status showLedPattern(RigIo& io, RigState state, std::chrono::duration<double> duration);

// Pulses the trigger `count` times, kTriggerSpacing apart. kBadInput without a trigger line.
Status pulseTriggers(RigIo& io, std::uint64_t count);

// Waits up to `timeout` for a debounced press: true when pressed, false at the timeout or on a
// stop request. kBadInput without a button line; the button's read error.
Result<bool> waitForButtonWithin(RigIo& io, std::chrono::milliseconds debounce,
                                 std::chrono::duration<double> timeout);

}  // namespace glarecam::rig
