#include "capture/daemon/stack_worker.h"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "pipeline/process_stack.h"

namespace glarecam::capture {

namespace fs = std::filesystem;

StackWorker::StackWorker(WorkerOptions options, EventQueue& events, DaemonClock& clock, Mode mode)
    : events_(events), clock_(clock), mode_(mode), options_(std::move(options)) {
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
  return captured_queued_ >= options_.max_backlog;
}

std::size_t StackWorker::pending() const {
  const std::lock_guard lock(mutex_);
  return jobs_.size() + (running_job_ ? 1 : 0);
}

std::optional<SteadyTime> StackWorker::busySince() const {
  const std::lock_guard lock(mutex_);
  return busy_since_;
}

bool StackWorker::submit(CapturedStack stack) {
  if (mode_ == Mode::kInline) {
    Job job{.stack = std::move(stack)};
    runJob(job, false);
    return true;
  }
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ || captured_queued_ >= options_.max_backlog) return false;
    jobs_.push_back({.stack = std::move(stack)});
    ++captured_queued_;
  }
  wake_.notify_one();
  return true;
}

void StackWorker::submitWritten(fs::path stack) {
  if (mode_ == Mode::kInline) {
    Job job{.path = std::move(stack)};
    runJob(job, false);
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    jobs_.push_back({.path = std::move(stack)});
  }
  wake_.notify_one();
}

void StackWorker::stop() {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
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
  const WorkerOptions options = currentOptions();
  try {
    if (job.stack) {
      const auto written = write(*job.stack, options, stopping);
      job.stack.reset();             // the frames' memory back before processing
      if (mode_ == Mode::kThread) {  // room for the next captured stack
        const std::lock_guard lock(mutex_);
        --captured_queued_;
      }
      if (!written) return;
      job.path = *written;
    }
    if (!stopping) process(job.path, options);  // else at the next start
  } catch (...) {  // a library's exception ends this job, not the daemon
    events_.post(WorkerEvent{.stage = WorkerEvent::Stage::kProcessed,
                             .stack_id = job.path.filename().string(),
                             .error = currentExceptionError(),
                             .last = true});
  }
}

std::optional<fs::path> StackWorker::write(const CapturedStack& stack, const WorkerOptions& options,
                                           bool last) {
  const std::string id = stack.manifest.id.value_or("stack");
  auto written = writeCapturedStack(options.day.root / kStacksDirectory, stack);
  WorkerEvent event{.stage = WorkerEvent::Stage::kWritten, .stack_id = id, .last = last};
  if (written) {
    event.stack_id = written->filename().string();
    event.path = *written;
    if (last) event.detail = "processing left for the next start";
  } else {
    event.error = written.error();
    event.last = true;
  }
  events_.post(std::move(event));
  if (!written) return std::nullopt;
  return *written;
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
