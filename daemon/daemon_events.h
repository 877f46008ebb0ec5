// What wakes glarecamd's event loop: signals, the operator's button and the stack worker's
// reports, as one std::variant posted to one queue from any thread and handled in one place (the
// loop thread). Timers are not events: the loop computes its next deadline and waits for it on the
// DaemonClock, so that a test's manual clock can jump there.
#pragma once

#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <variant>

#include "core/error.h"
#include "daemon/daemon_clock.h"
#include "daemon/status/result_brief.h"

namespace glarecam::daemon {

struct SignalEvent {
  int signal = 0;  // SIGTERM, SIGINT, SIGHUP, SIGUSR1
};

struct ButtonEvent {
  std::optional<Error> error{};  // the button could not be read (a press otherwise)
};

// The worker's progress with one stack: written (or not), processed (or not), its day's sweep
// table and data sheet updated (or not).
struct WorkerEvent {
  enum class Stage { kWritten, kProcessed, kPublished };
  Stage stage = Stage::kWritten;
  std::string stack_id{};
  std::filesystem::path path{};  // the stack, its result or the day's directory
  std::optional<Error> error{};
  std::string detail{};   // the result's brief report, the day's state
  bool last = false;      // the job's last event: the stack is done, one way or the other
  bool captured = false;  // a stack captured by this run (not one found on disk at start)
  std::optional<ResultBrief> result{};  // kProcessed without an error
  std::size_t day_stacks = 0;           // kPublished: the day's sweep table's rows
  bool day_datasheet = false;           // kPublished: the day's data sheet was (re)written
};

using DaemonEvent = std::variant<SignalEvent, ButtonEvent, WorkerEvent>;

class EventQueue {
 public:
  explicit EventQueue(DaemonClock& clock) : clock_(clock) {}
  EventQueue(const EventQueue&) = delete;
  EventQueue& operator=(const EventQueue&) = delete;

  // From any thread.
  void post(DaemonEvent event);
  // The oldest event, or nullopt once `deadline` has passed with none.
  std::optional<DaemonEvent> waitPop(SteadyTime deadline);
  // The oldest event if there is one, without waiting.
  std::optional<DaemonEvent> tryPop();

 private:
  DaemonClock& clock_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<DaemonEvent> events_;
};

}  // namespace glarecam::daemon
