// The clock check: adjtimex's state read as synchronised or not, with its error bound.
#include "sun/clock_sync.h"

#include <gtest/gtest.h>
#include <sys/timex.h>

namespace glarecam::sun {
namespace {

TEST(ClockStatus, InterpretsAdjtimex) {
  const sun::ClockStatus synced = sun::interpretClockState(TIME_OK, 0, 250000, 1200);
  EXPECT_TRUE(synced.synchronised);
  EXPECT_DOUBLE_EQ(*synced.uncertaintyS(), 0.0012);
  // Unsynchronised, the kernel's 16 s is a cap, not a bound: the error is unknown.
  const sun::ClockStatus error =
      sun::interpretClockState(TIME_ERROR, STA_UNSYNC, 16000000, 16000000);
  EXPECT_FALSE(error.synchronised);
  EXPECT_FALSE(error.uncertaintyS());
  EXPECT_NE(error.detail.find("unsynchronised"), std::string::npos);
  EXPECT_FALSE(sun::interpretClockState(TIME_OK, STA_UNSYNC, 0, 0).synchronised);
  EXPECT_FALSE(sun::interpretClockState(TIME_ERROR, 0, 0, 0).synchronised);
  EXPECT_TRUE(
      sun::interpretClockState(TIME_INS, STA_PLL, 1, 1).synchronised);  // leap second pending
}

}  // namespace
}  // namespace glarecam::sun
