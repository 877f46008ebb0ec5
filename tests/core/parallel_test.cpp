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

}  // namespace
}  // namespace glarecam
