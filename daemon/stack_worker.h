// The daemon's worker: everything a stack needs after its bracket, off the capture loop so that
// disk and CPU work never starve the camera stream. Each captured stack is written atomically
// under OUTPUT/stacks/ (nothing half-written is ever visible), then processed into
// OUTPUT/results/<id>/ and its day's sweep table and data sheet rebuilt (day_products.h), each
// stage reported to the event loop as a WorkerEvent. Writes go first: a captured stack, held in
// memory, never waits behind the processing of another. The thread runs at a lower priority
// (nice kWorkerNice) than the capture loop.
//
// The loop bounds what is held in memory (full(), checked before a bracket); a stack whose write
// fails (a full or read-only disk) is kept, not dropped: the loop pauses capture and calls
// retryParked() once the disk takes writes again; after kMaxWriteAttempts it is given up, loudly.
// A stack whose processing the system refused (kIo: its result could not be written) is parked
// the same way and processed again by retryParked(); after kMaxWriteAttempts it is left on disk,
// without a result, for the next start.
// stop() writes every stack still queued or kept, so that none is lost on shutdown unless the
// disk refuses it then too (reported), and processes none; the next start processes every stack
// without a result (submitWritten()). A stack that cannot be processed at all (bad data) gets a
// `<id>.failed` note beside the results, and is not processed again.
#pragma once

#include <condition_variable>
#include <deque>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "capture/bracketer.h"
#include "daemon/daemon_clock.h"
#include "daemon/daemon_events.h"
#include "daemon/storage/day_products.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

inline constexpr int kWorkerNice = 10;
// Writes of one kept stack tried while the disk looks fine, before it is given up.
inline constexpr int kMaxWriteAttempts = 10;

struct WorkerOptions {
  DayProductsOptions day;
  unsigned threads = 1;         // for processing
  std::size_t max_backlog = 2;  // captured stacks waiting to be written
};

class StackWorker {
 public:
  // kInline runs each job inside submit() (tests: one thread, deterministic).
  enum class Mode { kThread, kInline };

  // `job_hook` (tests) runs on the worker's thread at the start of every job.
  StackWorker(WorkerOptions options, EventQueue& events, DaemonClock& clock, Mode mode,
              std::function<void()> job_hook = {});
  ~StackWorker();  // stop()
  StackWorker(const StackWorker&) = delete;
  StackWorker& operator=(const StackWorker&) = delete;

  // For the jobs not yet started.
  void reconfigure(WorkerOptions options);

  // Queues a captured stack (the loop checked full() before the bracket: once captured, a stack
  // is always taken). False only after stop().
  bool submit(capture::CapturedStack stack);
  // Queues a stack already on disk for processing.
  void submitWritten(std::filesystem::path stack);

  // Queues the stacks whose write failed again, first.
  void retryParked();
  bool hasParked() const;

  bool full() const;            // captured stacks queued or kept reach the backlog
  std::size_t pending() const;  // jobs queued, running or kept
  // Since when the running job has been running (nullopt when idle): a job that never ends (a
  // hung disk) makes the daemon stop feeding the watchdog.
  std::optional<SteadyTime> busySince() const;

  // Writes the queued captured stacks, skips the rest, joins the thread. Idempotent.
  void stop();

 private:
  struct Job {
    std::optional<capture::CapturedStack> stack{};  // to write; else `path` is on disk already
    std::filesystem::path path{};
    bool captured = false;  // a stack of this run (WorkerEvent::captured)
    int attempts = 0;       // writes tried
    int process_attempts = 0;
  };

  void enqueue(Job job);
  void run(std::stop_token stop);
  void runJob(Job& job, bool stopping);
  // The next job (writes first; none but writes when stopping), or nullopt to end.
  std::optional<Job> nextJob(bool stopping);
  // The written stack's path; on failure the job is parked (or, when stopping, the stack lost).
  std::optional<std::filesystem::path> write(Job& job, const WorkerOptions& options, bool stopping);
  void process(Job& job, const WorkerOptions& options);
  std::string parkProcessing(Job& job);
  Result<pipeline::ProcessSummary> processInto(const std::filesystem::path& stack,
                                               const std::filesystem::path& target,
                                               const WorkerOptions& options);
  WorkerOptions currentOptions() const;

  EventQueue& events_;
  DaemonClock& clock_;
  Mode mode_;
  std::function<void()> job_hook_;

  mutable std::mutex mutex_;
  std::condition_variable_any wake_;
  WorkerOptions options_;
  std::deque<Job> writes_;             // captured stacks to write, oldest first
  std::deque<Job> processing_;         // stacks on disk to process
  std::deque<Job> parked_;             // captured stacks whose write failed, oldest first
  std::deque<Job> parked_processing_;  // stacks on disk whose processing the system refused
  std::optional<SteadyTime> busy_since_;
  bool running_job_ = false;
  bool running_write_ = false;
  bool stopping_ = false;
  std::jthread thread_;  // last: joined before the members it uses go
};

}  // namespace glarecam::daemon
