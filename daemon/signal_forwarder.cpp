#include "daemon/signal_forwarder.h"

#include <pthread.h>
#include <signal.h>

#include <chrono>

namespace glarecam::daemon {

namespace {

// How often the forwarder looks up from sigtimedwait to see whether it should end.
constexpr std::chrono::milliseconds kSignalPoll{200};

sigset_t daemonSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  for (const int signal : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, signal);
  return signals;
}

}  // namespace

void blockDaemonSignals() {
  const sigset_t signals = daemonSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
}

SignalForwarder::SignalForwarder(EventQueue& events) {
  thread_ = std::jthread([&events](std::stop_token stop) {
    const sigset_t signals = daemonSignals();
    const timespec poll{0, std::chrono::nanoseconds(kSignalPoll).count()};
    while (!stop.stop_requested()) {
      const int signal = sigtimedwait(&signals, nullptr, &poll);
      if (signal > 0) events.post(SignalEvent{signal});
    }
  });
}

SignalForwarder::~SignalForwarder() {
  thread_.request_stop();
  thread_.join();
}

}  // namespace glarecam::daemon
