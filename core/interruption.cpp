#include "core/interruption.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <ctime>
#include <thread>

namespace glarecam {

namespace {

// Set from a signal handler (on whichever thread the signal lands) and read from any thread: an
// atomic that needs no lock is both async-signal-safe and free of data races.
std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

void requestStop(int) { g_stop_requested.store(true); }

sigset_t stopSignals() {
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  return stop;
}

}  // namespace

void stopGracefullyOnSignals() {
  struct sigaction action {};
  action.sa_handler = requestStop;
  action.sa_flags = SA_RESETHAND;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stopRequested() { return g_stop_requested.load(); }

void sleepUntil(std::chrono::steady_clock::time_point deadline) {
  while (!stopRequested() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
        kStopPoll, deadline - std::chrono::steady_clock::now()));
  }
}

void blockStopSignals() {
  const sigset_t stop = stopSignals();
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
}

void waitForStopSignal(double seconds) {
  const sigset_t stop = stopSignals();
  if (seconds > 0) {
    const auto whole = static_cast<time_t>(seconds);
    const timespec timeout{whole, static_cast<long>((seconds - whole) * 1e9)};
    sigtimedwait(&stop, nullptr, &timeout);
  } else {
    int signal_number = 0;
    sigwait(&stop, &signal_number);
  }
}

}  // namespace glarecam
