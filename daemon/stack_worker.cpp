#include "daemon/stack_worker.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <string>

#include "core/atomic_file.h"
#include "daemon/storage/output_tree.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

namespace {

// The staging directories an earlier, refused try of stack `id` left in `directory`. Only the
// worker writes them, one job at a time, so none of them belongs to a writer still running.
void removeLeftoversOf(const fs::path& directory, std::string_view id) {
  const std::string_view names[] = {id};
  removeStaleTemporaries(directory, std::chrono::seconds(0), names);
}

}  // namespace

StackWorker::StackWorker(WorkerOptions options, EventQueue& events, DaemonClock& clock, Mode mode,
                         std::function<void()> job_hook)
    : events_(events),
      clock_(clock),
      mode_(mode),
      job_hook_(std::move(job_hook)),
      options_(std::move(options)) {
  if (mode_ == Mode::kThread) thread_ = std::jthread([this](std::stop_token stop) { run(stop); });
}

StackWorker::~StackWorker() { stop(); }

void StackWorker::reconfigure(WorkerOptions options) {
  const std::lock_guard lock(mutex_);
  options_ = std::move(options);
}

WorkerOptions StackWorker::currentOptions() const {
  const std::lock_guard lock(mutex_);
  return options_;
}

bool StackWorker::full() const {
  const std::lock_guard lock(mutex_);
  return writes_.size() + parked_.size() + (running_write_ ? 1 : 0) >= options_.max_backlog;
}

std::size_t StackWorker::pending() const {
  const std::lock_guard lock(mutex_);
  return writes_.size() + processing_.size() + parked_.size() + parked_processing_.size() +
         (running_job_ ? 1 : 0);
}

bool StackWorker::hasParked() const {
  const std::lock_guard lock(mutex_);
  return !parked_.empty() || !parked_processing_.empty();
}

std::optional<SteadyTime> StackWorker::busySince() const {
  const std::lock_guard lock(mutex_);
  return busy_since_;
}

void StackWorker::enqueue(Job job) {
  if (mode_ == Mode::kInline) {
    runJob(job, false);
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    (job.stack ? writes_ : processing_).push_back(std::move(job));
  }
  wake_.notify_one();
}

bool StackWorker::submit(capture::CapturedStack stack) {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_) return false;
  }
  enqueue({.stack = std::move(stack), .captured = true});
  return true;
}

void StackWorker::submitWritten(fs::path stack) { enqueue({.path = std::move(stack)}); }

void StackWorker::retryParked() {
  std::deque<Job> parked;
  {
    const std::lock_guard lock(mutex_);
    parked.swap(parked_);
    std::ranges::move(parked_processing_, std::back_inserter(parked));
    parked_processing_.clear();
    if (mode_ == Mode::kThread)
      for (auto job = parked.rbegin(); job != parked.rend(); ++job)
        (job->stack ? writes_ : processing_).push_front(std::move(*job));
  }
  if (mode_ == Mode::kThread) {
    wake_.notify_one();
    return;
  }
  for (Job& job : parked) runJob(job, false);
}

void StackWorker::stop() {
  std::deque<Job> parked;
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable() && parked_.empty()) return;
    stopping_ = true;  // from here on every write is the last try
    parked.swap(parked_);
    parked_processing_.clear();  // on disk already: the next start processes them
    if (mode_ == Mode::kThread)
      for (auto job = parked.rbegin(); job != parked.rend(); ++job)
        writes_.push_front(std::move(*job));
  }
  if (mode_ == Mode::kInline) {
    for (Job& job : parked) runJob(job, true);
    return;
  }
  if (thread_.joinable()) {
    thread_.request_stop();
    wake_.notify_all();
    thread_.join();
  }
}

std::optional<StackWorker::Job> StackWorker::nextJob(bool stopping) {
  std::deque<Job>& queue = !writes_.empty() ? writes_ : processing_;
  if (queue.empty() || (stopping && &queue == &processing_)) return std::nullopt;
  Job job = std::move(queue.front());
  queue.pop_front();
  return job;
}

void StackWorker::run(std::stop_token stop) {
  // Linux nice values are per thread: this lowers only the worker's priority.
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kWorkerNice) != 0)
    spdlog::debug("glarecamd: worker priority unchanged: {}", errnoText(errno));
  for (;;) {
    std::optional<Job> job;
    bool stopping = false;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, stop, [this] { return !writes_.empty() || !processing_.empty(); });
      // On stop: the captured stacks are still written; stacks on disk wait for the next start.
      stopping = stop.stop_requested() || stopping_;
      job = nextJob(stopping);
      if (!job) {
        if (stop.stop_requested()) return;
        continue;
      }
      running_job_ = true;
      running_write_ = job->stack.has_value();
      busy_since_ = clock_.now();
    }
    runJob(*job, stopping);
    const std::lock_guard lock(mutex_);
    running_job_ = running_write_ = false;
    busy_since_.reset();
  }
}

void StackWorker::runJob(Job& job, bool stopping) {
  if (job_hook_) job_hook_();
  const WorkerOptions options = currentOptions();
  const Status done = catchExceptions([&]() -> Status {
    if (job.stack) {
      const auto written = write(job, options, stopping);
      if (!written || stopping) return {};  // unwritten stacks are kept; processed at next start
      if (mode_ == Mode::kThread) {         // behind the other writes
        enqueue({.path = *written, .captured = job.captured});
        return {};
      }
      job.path = *written;
    }
    process(job, options);
    return {};
  });
  if (!done) {  // a library's exception ends this job, not the daemon
    events_.post(WorkerEvent{
        .stage = job.stack ? WorkerEvent::Stage::kWritten : WorkerEvent::Stage::kProcessed,
        .stack_id =
            job.stack ? job.stack->manifest.id.value_or("stack") : job.path.filename().string(),
        .error = done.error(),
        .last = true,
        .captured = job.captured});
  }
}

std::optional<fs::path> StackWorker::write(Job& job, const WorkerOptions& options, bool stopping) {
  const std::string id = job.stack->manifest.id.value_or("stack");
  const fs::path stacks = options.day.root / kStacksDirectory;
  // What a refused try left (a read-only remount stops the staging directory's removal too).
  if (job.attempts > 0) removeLeftoversOf(stacks, id);
  ++job.attempts;
  auto written = capture::writeCapturedStack(stacks, *job.stack);
  WorkerEvent event{.stage = WorkerEvent::Stage::kWritten,
                    .stack_id = id,
                    .last = stopping,
                    .captured = job.captured};
  if (written) {
    job.stack.reset();  // the frames' memory back before processing
    event.stack_id = written->filename().string();
    event.path = *written;
    if (stopping) event.detail = "processing left for the next start";
    events_.post(std::move(event));
    return *written;
  }
  event.error = written.error();
  const int attempts = job.attempts;
  {
    // stopping_ read under the lock stop() sets it with: a stack parked after stop() took the
    // parked ones would be lost without a word.
    const std::lock_guard lock(mutex_);
    stopping = stopping || stopping_;
    if (!stopping && attempts < kMaxWriteAttempts) parked_.push_back(std::move(job));
  }
  if (stopping || attempts >= kMaxWriteAttempts) {
    event.error->message +=
        fmt::format("; the stack is lost ({})",
                    stopping ? "glarecamd is stopping" : fmt::format("{} tries", attempts));
    event.last = true;
  }
  events_.post(std::move(event));
  return std::nullopt;
}

// The result appears whole like the stack: processed in a staging directory, then renamed (over
// the result of an earlier, interrupted processing).
Result<pipeline::ProcessSummary> StackWorker::processInto(const fs::path& stack,
                                                          const fs::path& target,
                                                          const WorkerOptions& options) {
  auto staging = StagingDirectory::create(target);
  if (!staging) return std::unexpected(staging.error());
  pipeline::ProcessOptions process;
  process.output_directory = staging->path();
  process.threads = options.threads;
  process.show_progress = false;
  // The rig's calibration is the operator's choice for this camera: a serial that differs is
  // logged as a warning, not a refusal that would mark every stack .failed for good.
  process.calibration_use.force = true;
  pipeline::ProcessSummary summary;
  GLARECAM_ASSIGN(summary, pipeline::processStack(stack, process));
  GLARECAM_CHECK(staging->commit());
  return summary;
}

// Parks a stack whose processing the system refused, for retryParked(). Empty when parked, else
// why it may not be tried again (kMaxWriteAttempts tries, or glarecamd is stopping).
std::string StackWorker::parkProcessing(Job& job) {
  const std::lock_guard lock(mutex_);
  if (stopping_) return "glarecamd is stopping";
  if (++job.process_attempts >= kMaxWriteAttempts)
    return fmt::format("{} tries", job.process_attempts);
  parked_processing_.push_back(job);
  return {};
}

void StackWorker::process(Job& job, const WorkerOptions& options) {
  const fs::path& stack = job.path;
  const std::string id = stack.filename().string();
  const fs::path results = options.day.root / kResultsDirectory;
  if (job.process_attempts > 0) removeLeftoversOf(results, id);
  const auto processed = processInto(stack, results / id, options);
  WorkerEvent event{
      .stage = WorkerEvent::Stage::kProcessed, .stack_id = id, .captured = job.captured};
  const auto day = stackDay(id, options.day.longitude_deg);
  event.last = !processed || !day;
  if (processed) {
    event.path = results / id;
    event.detail = processed->briefReport();
    event.result = resultBrief(processed->result);
  } else {
    event.error = processed.error();
    // Bad data stays bad: noted, so that no later start processes it again.
    if (processed.error().code == ErrorCode::kBadInput)
      (void)writeFileAtomic(results / (id + kFailedSuffix), processed.error().message + "\n");
    // A refused write (a full disk) passes: kept, and processed again once the disk takes writes.
    if (processed.error().code == ErrorCode::kIo) {
      const std::string not_parked = parkProcessing(job);
      if (not_parked.empty())
        event.last = false;
      else
        event.error->message +=
            fmt::format("; the stack is left for the next start ({})", not_parked);
    }
  }
  const bool publish = processed && day;
  events_.post(std::move(event));
  if (!publish) return;
  auto published = updateDayProducts(options.day, *day);
  WorkerEvent report{.stage = WorkerEvent::Stage::kPublished,
                     .stack_id = id,
                     .last = true,
                     .captured = job.captured};
  if (published) {
    report.path = published->directory;
    report.detail = published->detail;
    report.day_stacks = published->stacks;
    report.day_datasheet = published->datasheet;
  } else {
    report.error = published.error();
  }
  events_.post(std::move(report));
}

}  // namespace glarecam::daemon
