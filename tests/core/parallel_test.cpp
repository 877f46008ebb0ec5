#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace glarecam {
namespace {

TEST(ParallelRows, CoversEveryRowOnceInDisjointBands) {
  std::vector<std::atomic<int>> visits(1001);
  parallelRows(1001, 4, [&](int begin, int end) {
    for (int y = begin; y < end; ++y) ++visits[static_cast<std::size_t>(y)];
  });
  for (const auto& count : visits) EXPECT_EQ(count.load(), 1);
}

TEST(ParallelRows, RethrowsAWorkersExceptionInTheCaller) {
  // Band 3 of 4 throws (a worker thread, not the caller's band 0): the caller must see it.
  EXPECT_THROW(parallelRows(400, 4,
                            [](int begin, int) {
                              if (begin >= 300) throw std::runtime_error("band failed");
                            }),
               std::runtime_error);
}

// Every task runs once; the threads take the next task when free, so one long task does not hold
// up the rest: with two threads, the short tasks all run beside the long first one.
TEST(ParallelTasks, RunsEveryTaskOnceOnTheThreadsGiven) {
  constexpr int kTasks = 9;
  std::vector<std::atomic<int>> runs(kTasks);
  std::atomic<bool> long_task_running{true};
  std::atomic<int> beside_long{0};
  const std::uint64_t before = threadsStarted();
  parallelTasks(kTasks, 2, [&](int i) {
    EXPECT_EQ(availableThreads(), 1u);
    ++runs[static_cast<std::size_t>(i)];
    if (i == 0) {
      // Waits (bounded) until the other thread has taken every short task.
      for (int spin = 0; spin < 10000 && beside_long < kTasks - 1; ++spin)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      long_task_running = false;
    } else if (long_task_running) {
      ++beside_long;
    }
  });
  EXPECT_EQ(threadsStarted() - before, 1u);
  for (const auto& count : runs) EXPECT_EQ(count.load(), 1);
  EXPECT_EQ(beside_long.load(), kTasks - 1);

  const std::uint64_t serial = threadsStarted();
  int order = 0;
  parallelTasks(3, 1, [&](int i) { EXPECT_EQ(i, order++); });  // one thread: in order, here
  EXPECT_EQ(threadsStarted(), serial);
  EXPECT_EQ(order, 3);
  EXPECT_THROW(parallelTasks(4, 2,
                             [](int i) {
                               if (i == 3) throw std::runtime_error("task failed");
                             }),
               std::runtime_error);
}

// A budget holds on its thread while it lives, a band of parallelRows runs with one thread (no
// nested fan-out), and runTask's thread has the budget it was given; each start is counted.
TEST(ThreadBudget, BoundsTheThreadsBelowItAndCountsEveryStart) {
  const unsigned hardware = defaultThreadCount();
  EXPECT_EQ(availableThreads(), hardware);
  {
    const ThreadBudget three(3);
    EXPECT_EQ(availableThreads(), 3u);
    {
      const ThreadBudget unchanged(0);
      EXPECT_EQ(availableThreads(), 3u);
    }
    std::vector<std::atomic<unsigned>> inside(4);
    const std::uint64_t before = threadsStarted();
    parallelRows(4, 4, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) inside[static_cast<std::size_t>(i)] = availableThreads();
    });
    EXPECT_EQ(threadsStarted() - before, 3u);  // the caller runs the first band
    for (const auto& threads : inside) EXPECT_EQ(threads.load(), 1u);
    EXPECT_EQ(runTask(2, [] { return availableThreads(); }).get(), 2u);
    EXPECT_EQ(threadsStarted() - before, 4u);
    EXPECT_EQ(availableThreads(), 3u);
  }
  EXPECT_EQ(availableThreads(), hardware);
}

}  // namespace
}  // namespace glarecam
