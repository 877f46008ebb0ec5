// Ctrl-C and SIGTERM for long commands: the first signal asks to stop (a sleep or a wait ends
// early), a second ends the process; a server blocks them and waits for one. Signals change the
// process for good, so each test that sends one runs in a child process of its own.
#include "core/interruption.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <stop_token>
#include <thread>

namespace glarecam {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// Runs `child` in a forked process and returns its wait status; the child's exit code is what
// `child` returns (0: every check held).
int runInChild(const std::function<int()>& child) {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(child());
  EXPECT_GT(pid, 0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

// Sends `signal` to this process `after` from now, from another thread.
std::jthread signalAfter(std::chrono::milliseconds after, int signal) {
  return std::jthread([after, signal] {
    std::this_thread::sleep_for(after);
    ::kill(::getpid(), signal);
  });
}

bool exitedWith(int status, int code) { return WIFEXITED(status) && WEXITSTATUS(status) == code; }

TEST(Interruption, WithoutASignalASleepLastsUntilItsDeadline) {
  const auto start = Clock::now();
  sleepUntil(start + 3 * kStopPoll / 2);
  EXPECT_GE(Clock::now() - start, 3 * kStopPoll / 2);
  EXPECT_FALSE(stopRequested());
  sleepUntil(start);  // a deadline past returns at once
}

TEST(Interruption, TheFirstSignalAsksToStopAndEndsASleepEarly) {
  for (const int signal : {SIGINT, SIGTERM}) {
    const int status = runInChild([signal] {
      stopGracefullyOnSignals();
      if (stopRequested()) return 1;
      const auto start = Clock::now();
      const std::jthread sender = signalAfter(50ms, signal);
      sleepUntil(start + 60s);
      // Seen within a poll of the signal; half a minute of slack for a loaded machine is still
      // far below the sleep's minute.
      if (Clock::now() - start >= 30s) return 2;
      return stopRequested() ? 0 : 3;
    });
    EXPECT_TRUE(exitedWith(status, 0)) << "signal " << signal << ": status " << status;
  }
}

TEST(Interruption, ASecondSignalEndsTheProcessAtOnce) {
  const int status = runInChild([] {
    stopGracefullyOnSignals();
    ::raise(SIGINT);  // asks to stop: the process goes on
    if (!stopRequested()) return 1;
    ::raise(SIGINT);  // ends it, killed by the signal
    return 2;
  });
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
}

TEST(Interruption, AWaitGetsAStopTokenThatASignalRequests) {
  const int status = runInChild([] {
    stopGracefullyOnSignals();
    const std::jthread sender = signalAfter(50ms, SIGTERM);
    const bool stopped = untilStopRequested([](std::stop_token stop) {
      const auto give_up = Clock::now() + 30s;
      while (!stop.stop_requested() && Clock::now() < give_up) std::this_thread::sleep_for(1ms);
      return stop.stop_requested();
    });
    return stopped ? 0 : 1;
  });
  EXPECT_TRUE(exitedWith(status, 0)) << "status " << status;
}

TEST(Interruption, AWaitThatEndsOnItsOwnReturnsItsValueWithoutAStop) {
  const auto start = Clock::now();
  const int value =
      untilStopRequested([](std::stop_token stop) { return stop.stop_requested() ? 0 : 42; });
  EXPECT_EQ(value, 42);
  // The watching thread ends with the wait, within one poll: no sleep of its own left behind.
  EXPECT_LT(Clock::now() - start, 10 * kStopPoll);
}

TEST(Interruption, ABlockedStopSignalIsWaitedForNotDelivered) {
  const int status = runInChild([] {
    blockStopSignals();
    const auto start = Clock::now();
    waitForStopSignal(0.05);  // none comes: returns at the timeout
    if (Clock::now() - start < 50ms) return 1;
    const std::jthread sender = signalAfter(50ms, SIGTERM);  // blocked: would kill otherwise
    const auto waiting = Clock::now();
    waitForStopSignal(30);
    return Clock::now() - waiting < 25s ? 0 : 2;
  });
  EXPECT_TRUE(exitedWith(status, 0)) << "status " << status;
}

}  // namespace
}  // namespace glarecam
