// The daemon's signals as events. blockDaemonSignals() blocks SIGTERM, SIGINT, SIGHUP and SIGUSR1
// in the calling thread; called first in main, before any thread starts, every later thread
// inherits the mask, so that no signal interrupts a camera or a disk write half-way. A
// SignalForwarder's thread then takes them one by one (sigtimedwait) and posts each to the event
// loop, which handles them in order with everything else.
#pragma once

#include <thread>

#include "daemon/daemon_events.h"

namespace glarecam::daemon {

void blockDaemonSignals();

class SignalForwarder {
 public:
  explicit SignalForwarder(EventQueue& events);
  ~SignalForwarder();  // stops the thread (within kSignalPoll)
  SignalForwarder(const SignalForwarder&) = delete;
  SignalForwarder& operator=(const SignalForwarder&) = delete;

 private:
  std::jthread thread_;
};

}  // namespace glarecam::daemon
