// What a restarted glarecamd recalls of the run before it: the newest result, today's products
// (the site's solar day) and the stacks left unprocessed, read from a real directory tree; and
// what the status then shows of them.
#include "daemon/storage/earlier_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "daemon/daemon_test_support.h"
#include "daemon/output_test_support.h"
#include "pipeline/sweep.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;

struct EarlierRunTest : ::testing::Test {
  testing::TempDir dir;
  OutputTree tree{dir / "out"};

  void SetUp() override { ASSERT_TRUE(tree.prepare()); }
  // days/<day>/ with Table III's sweep (9 rows) and no data sheet.
  void makeDay(const std::string& day) const {
    fs::create_directories(tree.days() / day);
    fs::copy_file(testing::testDataDir() / "standard-module-table3.csv",
                  tree.days() / day / pipeline::kSweepTableFileName);
  }
};

TEST_F(EarlierRunTest, AFirstStartRecallsNothing) {
  const EarlierRun earlier = EarlierRun::read(tree, testing::utc("2026-06-21T12:00:00Z"), {});
  EXPECT_FALSE(earlier.last_result);
  EXPECT_FALSE(earlier.today);
  EXPECT_TRUE(earlier.unprocessed.empty());
  DaemonState state;
  earlier.recordInto(state);
  EXPECT_FALSE(state.last_result);
  EXPECT_FALSE(state.last_day);
  EXPECT_EQ(state.day, "");
}

TEST_F(EarlierRunTest, TheNewestResultTodaysProductsAndTheStacksLeftUnprocessed) {
  testing::makeProcessed(tree, "20260621T080000Z-a40.00");
  testing::makeGlarecamStack(tree.stacks() / "20260621T090000Z-a41.00");
  testing::makeGlarecamResult(tree.results() / "20260621T090000Z-a41.00", 2000);
  testing::makeGlarecamStack(tree.stacks() / "20260621T100000Z-a42.00");  // not processed yet
  testing::makeGlarecamStack(tree.stacks() / "20260621T070000Z-a39.00");  // processing failed
  testing::writeText(tree.results() / "20260621T070000Z-a39.00.failed", "bad stack\n");
  makeDay("2026-06-20");
  makeDay("2026-06-21");

  const EarlierRun earlier = EarlierRun::read(tree, testing::utc("2026-06-21T12:00:00Z"), {});
  ASSERT_TRUE(earlier.last_result);
  EXPECT_EQ(earlier.last_result->stack_id, "20260621T090000Z-a41.00");
  EXPECT_EQ(earlier.last_result->brief.lmax_cd_m2, 2000);
  ASSERT_TRUE(earlier.today);
  EXPECT_EQ(earlier.today->day, "2026-06-21");
  EXPECT_EQ(earlier.unprocessed,
            (std::vector<fs::path>{tree.stacks() / "20260621T100000Z-a42.00"}));

  DaemonState state;
  earlier.recordInto(state);
  ASSERT_TRUE(state.last_result);
  EXPECT_EQ(state.last_result->directory, tree.results() / "20260621T090000Z-a41.00");
  ASSERT_TRUE(state.last_day);
  EXPECT_EQ(state.last_day->day, "2026-06-21");
  EXPECT_EQ(state.last_day->stacks, 9u);
  EXPECT_FALSE(state.last_day->datasheet);
  EXPECT_EQ(state.day, "2026-06-21: 9 stacks; no data sheet yet");
}

// Today is the site's mean solar day: at 7.85° E, 23:50 UTC on the 21st is the 22nd; yesterday's
// sheet is not today's.
TEST_F(EarlierRunTest, TodayIsTheSitesSolarDay) {
  makeDay("2026-06-21");
  const UtcTime late = testing::utc("2026-06-21T23:50:00Z");
  EXPECT_EQ(EarlierRun::read(tree, late, std::nullopt).today.value().day, "2026-06-21");
  EXPECT_FALSE(EarlierRun::read(tree, late, 7.85).today);
  makeDay("2026-06-22");
  EXPECT_EQ(EarlierRun::read(tree, late, 7.85).today.value().day, "2026-06-22");
}

}  // namespace
}  // namespace glarecam::daemon
