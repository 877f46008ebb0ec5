#include "apps/glarecam/interruption.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <stop_token>
#include <thread>

#include "rig/gpio/button_debouncer.h"

namespace glarecam::apps {

namespace {

// Set from a signal handler (on whichever thread the signal lands) and read from any thread: an
// atomic that needs no lock is both async-signal-safe and free of data races.
std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

void requestStop(int) { g_stop_requested.store(true); }

// How soon a stop request ends a sleep or a wait.
constexpr std::chrono::milliseconds kStopPoll{100};

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

Result<bool> waitForButtonPress(rig::RigIo& io, std::chrono::milliseconds debounce,
                                rig::RigClock::time_point deadline) {
  // One wait (a press may straddle any slicing), stopped from a thread that watches for signals.
  std::stop_source stop;
  std::jthread signal_watch([&stop](std::stop_token done) {
    while (!done.stop_requested() && !stopRequested()) std::this_thread::sleep_for(kStopPoll);
    stop.request_stop();
  });
  rig::ButtonWatcher watcher(io, debounce);
  return watcher.waitForPress(deadline, stop.get_token());
}

}  // namespace glarecam::apps
