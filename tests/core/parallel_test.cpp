#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
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
