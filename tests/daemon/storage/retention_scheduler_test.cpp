// When glarecamd applies retention, on a real directory tree and the manual clock: a pass at start
// and after a stack (the age rules and the budget, the disk not looked at), one from the disk
// check below the reserve with a budget set (then a second look), none while the clock is not
// synchronised; each pass recorded in the status; the policy in the status page's words.
#include "daemon/storage/retention_scheduler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "daemon/daemon_test_support.h"
#include "daemon/output_test_support.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::makeProcessed;

constexpr const char* kOldStack = "20260621T080000Z-a10.00";
constexpr const char* kTodaysStack = "20260625T080000Z-a10.00";

// 25 June 2026, noon UTC: a stack of the 21st is four days old, one of the 25th today's.
struct RetentionSchedulerTest : ::testing::Test {
  testing::TempDir dir;
  testing::ManualClock clock{testing::utc("2026-06-25T12:00:00Z")};
  testing::RecordingNotifier notifier{clock};
  testing::ScriptedDisk disk;
  HealthMonitor health{clock, notifier, disk};
  OutputConfig output;
  OutputTree tree{dir / "out"};
  DaemonState state;

  void SetUp() override {
    output.root = tree.root();
    output.reserve_bytes = 100ull << 20;
    ASSERT_TRUE(tree.prepare());
    makeProcessed(tree, kOldStack);
    makeProcessed(tree, kTodaysStack);
  }
  bool stackLeft(const std::string& id) const { return fs::exists(tree.stacks() / id); }
  void setFree(std::uint64_t free_bytes, bool read_only = false) {
    disk.set({.free_bytes = free_bytes, .total_bytes = 100ull << 30, .read_only = read_only});
  }
};

TEST_F(RetentionSchedulerTest, APassAppliesTheAgeRulesAndIsRecordedInTheStatus) {
  output.retention.keep_stacks_days = 1;
  RetentionScheduler retention(clock, output, std::nullopt);
  EXPECT_EQ(retention.apply(state), 1u);
  EXPECT_FALSE(stackLeft(kOldStack));
  EXPECT_TRUE(stackLeft(kTodaysStack));
  EXPECT_TRUE(fs::exists(tree.results() / kOldStack));  // results are kept without their rule
  EXPECT_EQ(state.stacks_deleted, 1u);
  EXPECT_TRUE(state.retention_last.starts_with(std::string("deleted stack ") + kOldStack))
      << state.retention_last;
  EXPECT_EQ(state.retention_last_time, clock.utcNow());
  const UtcTime deleted_at = clock.utcNow();
  clock.advance(1h);
  EXPECT_EQ(retention.apply(state), 0u);  // nothing more may go: the last deletion's time stays
  EXPECT_EQ(state.retention_last_time, deleted_at);
  EXPECT_EQ(disk.probes(), 0);  // a pass at start or after a stack does not look at the disk
}

// At start a prune a power cut interrupted is finished, whatever the policy and the clock (the
// result already says "pruned"), and counted in the status.
TEST_F(RetentionSchedulerTest, StartFinishesAPruneCutShortEvenWithoutAPolicy) {
  const fs::path result = tree.results() / kOldStack;
  pipeline::StackResult document = pipeline::readResult(result / pipeline::kResultFileName).value();
  document.outputs.pruned_at = "2026-06-24T12:00:00Z";
  testing::writeText(result / pipeline::kResultFileName, jsonText(pipeline::toJson(document)));
  clock.setClockStatus({.synchronised = false, .detail = "no NTP"});
  RetentionScheduler retention(clock, output, std::nullopt);  // no policy
  EXPECT_EQ(retention.start(state), 1u);
  EXPECT_FALSE(fs::exists(result / "luminance.exr"));
  EXPECT_TRUE(fs::exists(result / pipeline::kResultFileName));
  EXPECT_TRUE(fs::exists(tree.results() / kTodaysStack / "luminance.exr"));  // never marked
  EXPECT_EQ(state.result_images_pruned, 1u);
  EXPECT_EQ(retention.start(state), 0u);
}

// Ages are told by the clock: while it is not synchronised (it may have run ahead) nothing goes.
TEST_F(RetentionSchedulerTest, NothingGoesWithoutAPolicyOrWhileTheClockIsUnsynchronised) {
  RetentionScheduler retention(clock, output, std::nullopt);
  EXPECT_EQ(retention.apply(state), 0u);
  output.retention.keep_stacks_days = 1;
  clock.setClockStatus({.synchronised = false, .detail = "no NTP"});
  retention.configure(output, std::nullopt);
  EXPECT_EQ(retention.apply(state), 0u);
  EXPECT_TRUE(stackLeft(kOldStack));
  EXPECT_EQ(state.stacks_deleted, 0u);
  clock.setClockStatus({.synchronised = true, .detail = "NTP"});
  EXPECT_EQ(retention.apply(state), 1u);
}

// Days are the site's mean solar days: at 7.85° E, 23:30 UTC on the 24th is already the 25th.
TEST_F(RetentionSchedulerTest, DaysAreTheSitesAfterAReloadToo) {
  makeProcessed(tree, "20260624T233000Z-a10.00");
  output.retention.keep_stacks_days = 1;
  RetentionScheduler retention(clock, output, 7.85);
  EXPECT_EQ(retention.apply(state), 1u);  // the 21st's
  EXPECT_TRUE(stackLeft("20260624T233000Z-a10.00"));
  retention.configure(output, std::nullopt);  // UTC days: the 24th's goes now
  EXPECT_EQ(retention.apply(state), 1u);
  EXPECT_FALSE(stackLeft("20260624T233000Z-a10.00"));
}

// Below the reserve with a budget set, the disk check frees the oldest stacks that may go and
// looks again; the scripted disk stays below, and the status says why nothing more may go.
TEST_F(RetentionSchedulerTest, BelowTheReserveWithABudgetItFreesAndLooksAgain) {
  output.retention.max_use_bytes = 1ull << 30;
  setFree(10ull << 20);
  RetentionScheduler retention(clock, output, std::nullopt);
  const HealthMonitor::DiskCheck check = retention.checkDisk(health, state);
  EXPECT_EQ(disk.probes(), 2);
  EXPECT_FALSE(stackLeft(kOldStack));
  EXPECT_TRUE(stackLeft(kTodaysStack));
  EXPECT_EQ(state.stacks_deleted, 1u);
  EXPECT_NE(check.pause_reason.find("below the 100.0 MiB reserve"), std::string::npos)
      << check.pause_reason;
  EXPECT_NE(state.retention_shortfall.find("nothing more may go"), std::string::npos)
      << state.retention_shortfall;
}

// The disk check alone never applies the age rules; below the reserve it frees space only with a
// budget set and a disk it can write to.
TEST_F(RetentionSchedulerTest, OtherwiseTheDiskCheckLooksOnceAndDeletesNothing) {
  output.retention.keep_stacks_days = 1;
  RetentionScheduler retention(clock, output, std::nullopt);
  EXPECT_TRUE(retention.checkDisk(health, state).pause_reason.empty());  // above the reserve
  EXPECT_EQ(disk.probes(), 1);
  setFree(10ull << 20);  // below, without a budget
  EXPECT_FALSE(retention.checkDisk(health, state).pause_reason.empty());
  EXPECT_EQ(disk.probes(), 2);
  output.retention.max_use_bytes = 1ull << 30;
  retention.configure(output, std::nullopt);
  setFree(10ull << 20, true);  // below, with a budget, read-only
  EXPECT_FALSE(retention.checkDisk(health, state).pause_reason.empty());
  EXPECT_EQ(disk.probes(), 3);
  EXPECT_TRUE(stackLeft(kOldStack));
  EXPECT_EQ(state.stacks_deleted, 0u);
}

TEST_F(RetentionSchedulerTest, ThePolicyInTheStatusPagesWords) {
  EXPECT_EQ(RetentionScheduler(clock, output, std::nullopt).policyText(),
            "off (nothing is deleted)");
  output.retention = {.keep_stacks_days = 7, .keep_results_days = 30, .max_use_bytes = 40ull << 30};
  EXPECT_EQ(RetentionScheduler(clock, output, std::nullopt).policyText(),
            "stacks 7 days, results 30 days, within 40.0 GiB");
  output.retention = RetentionPolicy{};
  output.retention.keep_results_days = 14;
  EXPECT_EQ(RetentionScheduler(clock, output, std::nullopt).policyText(), "results 14 days");
}

}  // namespace
}  // namespace glarecam::daemon
