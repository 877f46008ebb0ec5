// Ctrl-C and SIGTERM for commands that run a while (a capture series, a wait for the button, an
// LED pattern): the first signal asks them to stop at the next safe point, so that they finish
// what they were writing and release the hardware; a second signal ends the process at once.
#pragma once

#include <chrono>

#include "core/error.h"
#include "rig/gpio/rig_io.h"

namespace glarecam::apps {

void stopGracefullyOnSignals();
bool stopRequested();

// Sleeps until `deadline` or a stop request, whichever comes first.
void sleepUntil(std::chrono::steady_clock::time_point deadline);

// Waits for a debounced press of the rig's button until `deadline`: true when pressed, false at
// the deadline or on a stop request; the button's read errors.
Result<bool> waitForButtonPress(rig::RigIo& io, std::chrono::milliseconds debounce,
                                rig::RigClock::time_point deadline);

}  // namespace glarecam::apps
