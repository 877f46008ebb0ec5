// How many threads a step may use, and the one way glarecam starts them.
// - availableThreads(): the hardware's threads, unless a ThreadBudget on the calling thread says
//   fewer. processStack() sets one from --threads (and sweep gives each job its share), so every
//   step under it (decoding, the merge, the peak search, region counts, the picture, the EXR
//   encoders) keeps to N threads in all without each taking a parameter.
// - parallelRows: runs body(first_row, end_row) over [0, rows) split into contiguous bands, one
//   per thread. Bands are disjoint, so a body that writes only its own rows needs no lock. An
//   exception thrown in any band (out of memory, say) is rethrown in the caller once every band
//   has finished, instead of terminating the process from a worker thread. A band runs with a
//   budget of one thread: parallel steps inside it do not multiply the threads.
// - parallelTasks: runs body(i) for every i in [0, count) on up to `threads` threads (the caller
//   is one), each thread taking the next index when it is free: tasks of unequal length, listed
//   longest first, pack onto the threads with little idle time. Exceptions as parallelRows; each
//   task runs with a budget of one thread.
// - threadsStarted(): how many threads parallelRows(), parallelTasks() and runTask() have started
// in this
//   process, so that a test sees --threads 1 start none.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <future>
#include <thread>
#include <utility>
#include <vector>

namespace glarecam {

inline unsigned defaultThreadCount() { return std::max(1u, std::thread::hardware_concurrency()); }

namespace detail {
inline thread_local unsigned thread_budget = 0;  // 0: none set
inline std::atomic<std::uint64_t> threads_started{0};
}  // namespace detail

inline unsigned availableThreads() {
  return detail::thread_budget != 0 ? detail::thread_budget : defaultThreadCount();
}

inline std::uint64_t threadsStarted() { return detail::threads_started.load(); }

// While it lives, availableThreads() on this thread is `threads` (0: unchanged).
class ThreadBudget {
 public:
  explicit ThreadBudget(unsigned threads) : previous_(detail::thread_budget) {
    if (threads != 0) detail::thread_budget = threads;
  }
  ~ThreadBudget() { detail::thread_budget = previous_; }
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

 private:
  unsigned previous_;
};

// Runs task() on a new thread with a budget of `threads`; the future holds its result (or its
// exception).
template <typename Task>
auto runTask(unsigned threads, Task&& task) {
  ++detail::threads_started;
  return std::async(std::launch::async, [threads, task = std::forward<Task>(task)]() mutable {
    const ThreadBudget budget(threads);
    return task();
  });
}

template <typename Body>
void parallelTasks(int count, unsigned threads, Body&& body) {
  threads = std::clamp(threads, 1u, static_cast<unsigned>(std::max(count, 1)));
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(std::max(count, 0)));
  auto run = [&] {
    const ThreadBudget one(1);
    for (int i = next++; i < count; i = next++) {
      try {
        body(i);
      } catch (...) {
        errors[static_cast<std::size_t>(i)] = std::current_exception();
      }
    }
  };
  {
    std::vector<std::jthread> workers;
    workers.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) {
      ++detail::threads_started;
      workers.emplace_back(run);
    }
    run();
  }  // joins every worker
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

template <typename Body>
void parallelRows(int rows, unsigned threads, Body&& body) {
  threads = std::clamp(threads, 1u, static_cast<unsigned>(std::max(rows, 1)));
  if (threads == 1) {
    const ThreadBudget one(1);
    body(0, rows);
    return;
  }
  auto band = [&](unsigned i) {
    return static_cast<int>(static_cast<long long>(rows) * i / threads);
  };
  std::vector<std::exception_ptr> errors(threads);
  auto run = [&](unsigned i) {
    const ThreadBudget one(1);
    try {
      body(band(i), band(i + 1));
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> workers;
    workers.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) {
      ++detail::threads_started;
      workers.emplace_back(run, i);
    }
    run(0);
  }  // joins every worker
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace glarecam
