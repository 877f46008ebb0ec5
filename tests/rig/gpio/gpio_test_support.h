// For the tests of the rig's GPIO: a clock the test advances (nothing sleeps on it) and a config
// with every line.
#pragma once

#include <chrono>
#include <string>

#include "rig/gpio/rig_io.h"

namespace glarecam::testing {

// Simulated time: the tests advance it; nothing here sleeps on it.
struct FakeClock {
  rig::RigClock::time_point now =
      rig::RigClock::time_point(std::chrono::seconds(1000));  // any origin
  rig::RigClockFunction function() {
    return [this] { return now; };
  }
};

inline rig::RigIoConfig allLines() {
  rig::RigIoConfig config;
  config.trigger = rig::GpioLine{17u};
  config.led = rig::GpioLine{27u};
  config.button = rig::GpioLine{std::string("BUTTON"), true};
  return config;
}

}  // namespace glarecam::testing
