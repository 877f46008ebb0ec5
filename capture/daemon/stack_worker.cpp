#include "capture/daemon/stack_worker.h"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "pipeline/process_stack.h"

namespace glarecam::capture {

namespace fs = std::filesystem;

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
  return captured_queued_ + parked_.size() >= options_.max_backlog;
}

std::size_t StackWorker::pending() const {
  const std::lock_guard lock(mutex_);
  return jobs_.size() + parked_.size() + (running_job_ ? 1 : 0);
}

bool StackWorker::hasParked() const {
  const std::lock_guard lock(mutex_);
  return !parked_.empty();
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
    if (job.stack) ++captured_queued_;
    jobs_.push_back(std::move(job));
  }
  wake_.notify_one();
}

bool StackWorker::submit(CapturedStack stack) {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ || captured_queued_ + parked_.size() >= options_.max_backlog) return false;
  }
  enqueue({.stack = std::move(stack)});
  return true;
}

void StackWorker::submitWritten(fs::path stack) { enqueue({.path = std::move(stack)}); }

void StackWorker::retryParked() {
  std::deque<Job> parked;
  {
    const std::lock_guard lock(mutex_);
    parked.swap(parked_);
    if (mode_ == Mode::kThread) {
      captured_queued_ += parked.size();
      for (auto job = parked.rbegin(); job != parked.rend(); ++job)
        jobs_.push_front(std::move(*job));
    }
  }
  if (mode_ == Mode::kThread) {
    wake_.notify_one();
    return;
  }
  for (Job& job : parked) runJob(job, false);
}

void StackWorker::stop() {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
  }
  retryParked();  // one more try for the kept stacks
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  if (thread_.joinable()) {
    thread_.request_stop();
    wake_.notify_all();
    thread_.join();
  }
}

void StackWorker::run(std::stop_token stop) {
  // Linux nice values are per thread: this lowers only the worker's priority.
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kWorkerNice) != 0)
    spdlog::debug("glarecamd: worker priority unchanged: {}", errnoText(errno));
  for (;;) {
    Job job;
    bool stopping = false;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, stop, [this] { return !jobs_.empty(); });
      stopping = stop.stop_requested();
      // On stop: the captured stacks are still written; stacks on disk wait for the next start.
      while (stopping && !jobs_.empty() && !jobs_.front().stack) jobs_.pop_front();
      if (jobs_.empty()) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      if (job.stack) --captured_queued_;
      running_job_ = true;
      busy_since_ = clock_.now();
    }
    runJob(job, stopping);
    const std::lock_guard lock(mutex_);
    running_job_ = false;
    busy_since_.reset();
  }
}

void StackWorker::runJob(Job& job, bool stopping) {
  if (job_hook_) job_hook_();
  const WorkerOptions options = currentOptions();
  try {
    if (job.stack) {
      const auto written = write(job, options, stopping);
      if (!written) return;
      job.path = *written;
    }
    if (!stopping) process(job.path, options);  // else at the next start
  } catch (...) {  // a library's exception ends this job, not the daemon
    events_.post(WorkerEvent{
        .stage = job.stack ? WorkerEvent::Stage::kWritten : WorkerEvent::Stage::kProcessed,
        .stack_id =
            job.stack ? job.stack->manifest.id.value_or("stack") : job.path.filename().string(),
        .error = currentExceptionError(),
        .last = true});
  }
}

std::optional<fs::path> StackWorker::write(Job& job, const WorkerOptions& options, bool stopping) {
  const std::string id = job.stack->manifest.id.value_or("stack");
  auto written = writeCapturedStack(options.day.root / kStacksDirectory, *job.stack);
  WorkerEvent event{.stage = WorkerEvent::Stage::kWritten, .stack_id = id, .last = stopping};
  if (written) {
    job.stack.reset();  // the frames' memory back before processing
    event.stack_id = written->filename().string();
    event.path = *written;
    if (stopping) event.detail = "processing left for the next start";
    events_.post(std::move(event));
    return *written;
  }
  event.error = written.error();
  if (stopping) {
    event.error->message += "; the stack is lost (glarecamd is stopping)";
  } else {  // kept for retryParked()
    const std::lock_guard lock(mutex_);
    parked_.push_back(std::move(job));
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
  pipeline::ProcessSummary summary;
  GLARECAM_ASSIGN(summary, pipeline::processStack(stack, process));
  GLARECAM_CHECK(staging->commit());
  return summary;
}

void StackWorker::process(const fs::path& stack, const WorkerOptions& options) {
  const std::string id = stack.filename().string();
  const auto processed = processInto(stack, options.day.root / kResultsDirectory / id, options);
  WorkerEvent event{.stage = WorkerEvent::Stage::kProcessed, .stack_id = id};
  if (processed) {
    event.path = options.day.root / kResultsDirectory / id;
    event.detail = processed->briefReport();
  } else {
    event.error = processed.error();
  }
  const auto day = stackDay(id, options.day.longitude_deg);
  const bool last = !processed || !day;
  event.last = last;
  events_.post(std::move(event));
  if (last) return;
  auto published = updateDayProducts(options.day, *day);
  WorkerEvent report{.stage = WorkerEvent::Stage::kPublished, .stack_id = id, .last = true};
  if (published) {
    report.path = published->directory;
    report.detail = published->detail;
  } else {
    report.error = published.error();
  }
  events_.post(std::move(report));
}

}  // namespace glarecam::capture
