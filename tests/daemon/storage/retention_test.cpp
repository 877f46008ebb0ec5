// Retention on a real directory tree: what goes by age and by space, oldest first, and everything
// that must never go (unprocessed, failed, today's, undated, not glarecam's, outside the root).
#include "daemon/storage/retention.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/time.h"
#include "daemon/output_test_support.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using testing::makeGlarecamResult;
using testing::makeGlarecamStack;
using testing::makeProcessed;
using testing::TempDir;
using testing::writeText;

constexpr std::uint64_t kMiB = 1 << 20;

UtcTime utcAt(const char* iso) { return parseIsoTime(iso).value(); }

std::vector<std::string> entryNames(const fs::path& directory) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(directory))
    found.push_back(entry.path().filename().string());
  std::ranges::sort(found);
  return found;
}

std::vector<std::string> deletedOf(const RetentionSummary& summary, const std::string& kind) {
  std::vector<std::string> found;
  for (const RetentionDeletion& d : summary.deleted)
    if (d.kind == kind) found.push_back(d.name);
  return found;
}

struct RetentionTest : ::testing::Test {
  TempDir dir;
  OutputTree tree{dir / "out"};
  void SetUp() override { ASSERT_TRUE(tree.prepare()); }
};

TEST_F(RetentionTest, NothingGoesWithoutASetting) {
  makeProcessed(tree, "20200101T000000Z-a10.00");
  const RetentionSummary summary = applyRetention(tree, {}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_TRUE(summary.deleted.empty());
  EXPECT_EQ(entryNames(tree.stacks()).size(), 1u);
}

// keep_stacks_days 2 on 25 June: the stacks of the 21st, 22nd and 23rd go (2 days old and more),
// those of the 24th and today stay; so do every stack that must never go, however old.
TEST_F(RetentionTest, StacksOlderThanTheirDaysGoOnlyWhenProcessedAndGlarecams) {
  for (const char* id :
       {"20260621T080000Z-a10.00", "20260622T080000Z-a10.00", "20260623T235959Z-a10.00",
        "20260624T000000Z-a10.00", "20260625T080000Z-a10.00"})
    makeProcessed(tree, id);
  makeGlarecamStack(tree.stacks() / "20260601T080000Z-a20.00");  // unprocessed
  makeGlarecamStack(tree.stacks() / "20260602T080000Z-a20.00");  // processing failed
  writeText(tree.results() / "20260602T080000Z-a20.00.failed", "bad frames");
  makeGlarecamStack(tree.stacks() /
                    "20260603T080000Z-a20.00");  // a result being written: no result.json
  fs::create_directories(tree.results() / "20260603T080000Z-a20.00");
  makeGlarecamStack(tree.stacks() / "my-calibration-run");  // no time in its name: undated
  makeGlarecamResult(tree.results() / "my-calibration-run");
  fs::create_directories(tree.stacks() / "20260604T080000Z-notes");  // no manifest: not ours
  writeText(tree.stacks() / "20260604T080000Z-notes" / "readme.txt", "keep");
  makeGlarecamResult(tree.results() / "20260604T080000Z-notes");
  // A link to a stack outside the root: neither followed nor deleted.
  makeGlarecamStack(dir / "elsewhere" / "20260605T080000Z-a30.00");
  makeGlarecamResult(tree.results() / "20260605T080000Z-a30.00");
  fs::create_directory_symlink(dir / "elsewhere" / "20260605T080000Z-a30.00",
                               tree.stacks() / "20260605T080000Z-a30.00");

  const RetentionSummary summary =
      applyRetention(tree, {.keep_stacks_days = 2}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_TRUE(summary.errors.empty());
  EXPECT_EQ(deletedOf(summary, "stack"),
            (std::vector<std::string>{"20260621T080000Z-a10.00", "20260622T080000Z-a10.00",
                                      "20260623T235959Z-a10.00"}));
  for (const RetentionDeletion& d : summary.deleted) {
    EXPECT_EQ(d.reason, "older than 2 days");
    EXPECT_EQ(d.bytes, 1000u + 30u);  // the frame and the manifest
  }
  EXPECT_EQ(summary.freed_bytes, 3 * 1030u);
  EXPECT_EQ(entryNames(tree.stacks()),
            (std::vector<std::string>{"20260601T080000Z-a20.00", "20260602T080000Z-a20.00",
                                      "20260603T080000Z-a20.00", "20260604T080000Z-notes",
                                      "20260605T080000Z-a30.00", "20260624T000000Z-a10.00",
                                      "20260625T080000Z-a10.00", "my-calibration-run"}));
  EXPECT_TRUE(fs::exists(dir / "elsewhere" / "20260605T080000Z-a30.00" / "frame-0.png"));
  // The results stay: keep_results_days is not set.
  EXPECT_TRUE(fs::exists(tree.results() / "20260621T080000Z-a10.00" / "result.json"));
}

// Days are the site's solar days, as the day sheets count them: at 15° E a stack taken at 23:30
// UTC belongs to the next day, here today, and stays.
TEST_F(RetentionTest, TodayIsTheSitesSolarDay) {
  makeProcessed(tree, "20260624T233000Z-a10.00");
  makeProcessed(tree, "20260624T223000Z-a10.00");
  const RetentionSummary summary = applyRetention(
      tree, {.keep_stacks_days = 1}, {.now = utcAt("2026-06-25T12:00:00Z"), .longitude_deg = 15.0});
  EXPECT_EQ(deletedOf(summary, "stack"), std::vector<std::string>{"20260624T223000Z-a10.00"});
}

// Results and day sheets by their own setting, each result only once its stack is gone; a day
// directory is known by its name and its sweep.csv.
TEST_F(RetentionTest, ResultsAndDaysGoByTheirOwnSettingAfterTheirStacks) {
  makeProcessed(tree, "20260610T080000Z-a10.00");
  makeProcessed(tree, "20260620T080000Z-a10.00");
  makeProcessed(tree, "20260624T080000Z-a10.00");
  makeGlarecamResult(tree.results() / "20260601T080000Z-a10.00");  // its stack went earlier
  writeText(tree.results() / "20260601T090000Z-a10.00.failed", "kept: it marks a failed stack");
  for (const char* day : {"2026-06-01", "2026-06-10", "2026-06-24"}) {
    fs::create_directories(tree.days() / day);
    writeText(tree.days() / day / "sweep.csv", "alpha_deg\n");
  }
  fs::create_directories(tree.days() / "2026-06-02");  // no sweep.csv: not a day of ours
  writeText(tree.days() / "2026-06-02" / "photo.jpg", "operator's");
  fs::create_directories(tree.days() / "archive");

  const RetentionSummary summary =
      applyRetention(tree, {.keep_stacks_days = 3, .keep_results_days = 10},
                     {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_EQ(deletedOf(summary, "stack"),
            (std::vector<std::string>{"20260610T080000Z-a10.00", "20260620T080000Z-a10.00"}));
  // 20260610's result goes with its stack in the same pass (15 days); 20260620's (5 days) stays.
  EXPECT_EQ(deletedOf(summary, "result"),
            (std::vector<std::string>{"20260601T080000Z-a10.00", "20260610T080000Z-a10.00"}));
  EXPECT_EQ(deletedOf(summary, "day"), (std::vector<std::string>{"2026-06-01", "2026-06-10"}));
  EXPECT_EQ(entryNames(tree.results()),
            (std::vector<std::string>{"20260601T090000Z-a10.00.failed", "20260620T080000Z-a10.00",
                                      "20260624T080000Z-a10.00"}));
  EXPECT_EQ(entryNames(tree.days()),
            (std::vector<std::string>{"2026-06-02", "2026-06-24", "archive"}));
}

// The space rule: the oldest stacks that may go, until the tree is within its budget.
TEST_F(RetentionTest, OldestStacksGoUntilTheTreeIsWithinItsBudget) {
  for (const char* id : {"20260620T080000Z-a10.00", "20260621T080000Z-a10.00",
                         "20260622T080000Z-a10.00", "20260623T080000Z-a10.00"})
    makeProcessed(tree, id, kMiB);
  makeProcessed(tree, "20260625T080000Z-a10.00", kMiB);  // today's
  // 5 stacks of 1 MiB and a little: a 2.5 MiB budget keeps two of them.
  const RetentionSummary summary =
      applyRetention(tree, {.max_use_bytes = 5 * kMiB / 2}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_EQ(deletedOf(summary, "stack"),
            (std::vector<std::string>{"20260620T080000Z-a10.00", "20260621T080000Z-a10.00",
                                      "20260622T080000Z-a10.00"}));
  EXPECT_LE(summary.used_bytes, 5 * kMiB / 2);
  EXPECT_GT(summary.used_bytes, 2 * kMiB);
  EXPECT_TRUE(summary.shortfall.empty()) << summary.shortfall;
  EXPECT_NE(summary.deleted.front().reason.find("over the 2.5 MiB budget"), std::string::npos)
      << summary.deleted.front().reason;
}

// What may not go stays even over the budget, and the summary says why.
TEST_F(RetentionTest, ABudgetThatCannotBeMetSaysWhy) {
  makeProcessed(tree, "20260620T080000Z-a10.00", kMiB);
  makeGlarecamStack(tree.stacks() / "20260621T080000Z-a10.00", kMiB);  // unprocessed
  makeProcessed(tree, "20260625T080000Z-a10.00", kMiB);                // today's
  const RetentionSummary summary =
      applyRetention(tree, {.max_use_bytes = kMiB}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_EQ(deletedOf(summary, "stack"), std::vector<std::string>{"20260620T080000Z-a10.00"});
  EXPECT_NE(summary.shortfall.find("over the 1.0 MiB budget"), std::string::npos)
      << summary.shortfall;
  EXPECT_NE(summary.shortfall.find("1 unprocessed, 1 of today"), std::string::npos)
      << summary.shortfall;
}

// Below the reserve (something else filled the disk) with a budget set: stacks go, oldest first,
// until the disk would have its reserve free again, though the tree is within its budget.
TEST_F(RetentionTest, StacksGoWhileTheDiskIsBelowItsReserve) {
  for (const char* id :
       {"20260620T080000Z-a10.00", "20260621T080000Z-a10.00", "20260622T080000Z-a10.00"})
    makeProcessed(tree, id, kMiB);
  const RetentionContext below{
      .now = utcAt("2026-06-25T12:00:00Z"),
      .disk = DiskState{.free_bytes = 3 * kMiB / 2, .total_bytes = 100 * kMiB},
      .reserve_bytes = 3 * kMiB};
  const RetentionSummary summary = applyRetention(tree, {.max_use_bytes = 100 * kMiB}, below);
  EXPECT_EQ(deletedOf(summary, "stack"),
            (std::vector<std::string>{"20260620T080000Z-a10.00", "20260621T080000Z-a10.00"}));
  EXPECT_NE(summary.deleted.front().reason.find("below the 3.0 MiB reserve"), std::string::npos);
  EXPECT_TRUE(summary.shortfall.empty()) << summary.shortfall;
  // Without a budget the reserve alone deletes nothing: the age settings decide.
  makeProcessed(tree, "20260623T080000Z-a10.00", kMiB);
  EXPECT_TRUE(applyRetention(tree, {.keep_stacks_days = 30}, below).deleted.empty());
}

// A deletion cut short leaves only a hidden temporary, which the next start removes.
TEST_F(RetentionTest, ADeletionCutShortLeavesOnlyATemporary) {
  makeProcessed(tree, "20260620T080000Z-a10.00");
  const fs::path doomed = tree.stacks() / (std::string(kTemporaryPrefix) + "deleted-x");
  fs::create_directories(doomed);
  writeText(doomed / "frame-0.png", "half gone");
  const RetentionSummary summary =
      applyRetention(tree, {.keep_stacks_days = 1}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_EQ(summary.deleted.size(), 1u);
  EXPECT_EQ(tree.removeLeftovers(), 1u);
  EXPECT_TRUE(entryNames(tree.stacks()).empty());
}

TEST(RetentionPolicy, ValidateNamesTheSetting) {
  const auto refused = [](const RetentionPolicy& policy, const char* text) {
    const Status valid = policy.validate();
    ASSERT_FALSE(valid) << text;
    EXPECT_NE(valid.error().message.find(text), std::string::npos) << valid.error().message;
  };
  refused({.keep_stacks_days = 0}, "keep_stacks_days: must be between 1 and 36500");
  refused({.keep_results_days = 36501}, "keep_results_days: must be between");
  refused({.keep_stacks_days = 10, .keep_results_days = 5}, "must be at least keep_stacks_days");
  refused({.max_use_bytes = 0}, "max_use_gib: must be positive");
  EXPECT_TRUE((RetentionPolicy{.keep_stacks_days = 5, .keep_results_days = 5}.validate()));
  EXPECT_FALSE(RetentionPolicy{}.enabled());
}

}  // namespace
}  // namespace glarecam::daemon
