// Ctrl-C and SIGTERM for commands that run a while (a capture series, a wait for the button, an
// LED pattern): the first signal asks them to stop at the next safe point, so that they finish
// what they were writing and release the hardware; a second signal ends the process at once.
#pragma once

#include <chrono>
#include <stop_token>

namespace glarecam {

void stopGracefullyOnSignals();
bool stopRequested();

// Sleeps until `deadline` or a stop request, whichever comes first.
void sleepUntil(std::chrono::steady_clock::time_point deadline);

// Calls `wait` with a stop token that is requested once a stop is (polled from a thread): for a
// blocking wait that takes a std::stop_token, such as a button's.
template <typename Wait>
auto untilStopRequested(Wait&& wait);

// How soon a stop request ends a sleep or a wait.
inline constexpr std::chrono::milliseconds kStopPoll{100};

// For a process that serves until stopped (glarecam fake-camera): blocks SIGINT and SIGTERM in
// this thread and every thread it starts after, so that only waitForStopSignal() receives them.
void blockStopSignals();
// Waits for SIGINT or SIGTERM (blocked by blockStopSignals()), at most `seconds` when positive.
void waitForStopSignal(double seconds);

}  // namespace glarecam

#include <thread>

template <typename Wait>
auto glarecam::untilStopRequested(Wait&& wait) {
  std::stop_source stop;
  std::jthread watch([&stop](std::stop_token done) {
    while (!done.stop_requested() && !stopRequested()) std::this_thread::sleep_for(kStopPoll);
    stop.request_stop();
  });
  return std::forward<Wait>(wait)(stop.get_token());
}
