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
#include "daemon/storage/day_products.h"
#include "pipeline/contour_table.h"
#include "pipeline/sweep_table.h"
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

// ---- by value: the tiers ---------------------------------------------------------------------

constexpr std::uint64_t kKiB = 1 << 10;

// The stack ids of a day's sweep table, as written.
std::vector<std::string> tableIds(const OutputTree& tree, const std::string& day) {
  std::vector<std::string> ids;
  const auto table = pipeline::readSweepTable(tree.days() / day / pipeline::kSweepTableFileName);
  EXPECT_TRUE(table) << (table ? "" : table.error().message);
  if (table)
    for (const pipeline::SweepRow& row : table->rows) ids.push_back(row.stack_id);
  std::ranges::sort(ids);
  return ids;
}

struct RetentionTiersTest : RetentionTest {
  // Three past days of two processed stacks each (stacks of 100 KiB, three images of 20 KiB per
  // result), the day tables of the first two written from their results (the third's never was:
  // its results cannot go whole), and one stack of today.
  static constexpr const char* kToday = "2026-06-25T12:00:00Z";
  const std::vector<std::string> past{"20260620T080000Z-a40.00", "20260620T100000Z-a20.00",
                                      "20260621T080000Z-a40.00", "20260621T100000Z-a20.00",
                                      "20260622T080000Z-a40.00", "20260622T100000Z-a20.00"};
  const std::string today_id = "20260625T080000Z-a40.00";
  void SetUp() override {
    RetentionTest::SetUp();
    for (const std::string& id : past) {
      makeGlarecamStack(tree.stacks() / id, 100 * kKiB);
      makeGlarecamResult(tree.results() / id, 50000, id.ends_with("40.00") ? 40.0 : 20.0,
                         20 * kKiB);
    }
    makeGlarecamStack(tree.stacks() / today_id, 100 * kKiB);
    makeGlarecamResult(tree.results() / today_id, 50000, 40.0, 20 * kKiB);
    const DayProductsOptions day{.root = tree.root(), .longitude_deg = std::nullopt};
    for (const char* d : {"2026-06-20", "2026-06-21"}) ASSERT_TRUE(updateDayProducts(day, d));
  }
  std::vector<std::string> kinds(const RetentionSummary& summary) const {
    std::vector<std::string> found;
    for (const RetentionDeletion& d : summary.deleted) found.push_back(d.kind);
    return found;
  }
};

// Under a budget nothing of a past day can meet, everything that may go goes, tier by tier, each
// oldest first: the stacks, then the results' images, then the results whose rows are in their
// day's table. Today's stack, and the results of the day without a table, stay; the shortfall
// names them.
TEST_F(RetentionTiersTest, PastDaysGiveStacksThenImagesThenResultsEachOldestFirst) {
  const RetentionSummary summary =
      applyRetention(tree, {.max_use_bytes = 1}, {.now = utcAt(kToday)});
  EXPECT_TRUE(summary.errors.empty());
  std::vector<std::string> expected_kinds(6, kDeletedStack);
  expected_kinds.insert(expected_kinds.end(), 6, kDeletedResultImages);
  expected_kinds.insert(expected_kinds.end(), 4, kDeletedResult);
  EXPECT_EQ(kinds(summary), expected_kinds);
  EXPECT_EQ(deletedOf(summary, kDeletedStack), past);
  EXPECT_EQ(deletedOf(summary, kDeletedResultImages), past);
  EXPECT_EQ(deletedOf(summary, kDeletedResult),
            (std::vector<std::string>(past.begin(), past.begin() + 4)));
  for (const RetentionDeletion& d : summary.deleted) {
    if (d.kind == kDeletedResultImages) {
      EXPECT_EQ(d.bytes, 3 * 20 * kKiB);
    }
  }
  EXPECT_EQ(entryNames(tree.stacks()), std::vector<std::string>{today_id});
  EXPECT_EQ(entryNames(tree.results()), (std::vector<std::string>{past[4], past[5], today_id}));
  EXPECT_NE(summary.shortfall.find("stacks kept: 1 of today"), std::string::npos)
      << summary.shortfall;
  EXPECT_NE(summary.shortfall.find("results kept: 2 not in their day's sweep.csv"),
            std::string::npos)
      << summary.shortfall;
  EXPECT_TRUE(summary.day_overflows);  // today's stack alone is over 1 byte
  EXPECT_NE(summary.shortfall.find("day directories "), std::string::npos) << summary.shortfall;
  // Today's result keeps its images; the pruned ones say so and keep their numbers.
  EXPECT_TRUE(fs::exists(tree.results() / today_id / "luminance.exr"));
  for (const std::string& id : {past[4], past[5]}) {
    const auto result = pipeline::readResult(tree.results() / id / pipeline::kResultFileName);
    ASSERT_TRUE(result) << result.error().message;
    EXPECT_EQ(result->outputs.pruned_at, "2026-06-25T12:00:00Z");
    EXPECT_EQ(result->luminance.max_cd_m2, 50000);
    EXPECT_FALSE(fs::exists(tree.results() / id / "luminance.png"));
  }
  // Every stack written keeps its numbers: a row in its day's table, or its result.json.
  EXPECT_EQ(tableIds(tree, "2026-06-20"), (std::vector<std::string>{past[0], past[1]}));
  EXPECT_EQ(tableIds(tree, "2026-06-21"), (std::vector<std::string>{past[2], past[3]}));
}

// Each tier stops once the tree fits: a budget that the stacks and three results' images meet
// leaves the other images and every result.
TEST_F(RetentionTiersTest, EachTierStopsOnceTheTreeFits) {
  const std::uint64_t before =
      applyRetention(tree, {.max_use_bytes = 1ull << 40}, {.now = utcAt(kToday)}).used_bytes;
  // 6 stacks and 3 images sets off: between what they free and what the next image would.
  const std::uint64_t stacks = 6 * (100 * kKiB + 30), images = 3 * (3 * 20 * kKiB);
  const RetentionSummary summary = applyRetention(
      tree, {.max_use_bytes = before - stacks - images + 10 * kKiB}, {.now = utcAt(kToday)});
  EXPECT_EQ(deletedOf(summary, kDeletedStack), past);
  EXPECT_EQ(deletedOf(summary, kDeletedResultImages),
            (std::vector<std::string>(past.begin(), past.begin() + 3)));
  EXPECT_TRUE(deletedOf(summary, kDeletedResult).empty());
  EXPECT_TRUE(summary.shortfall.empty()) << summary.shortfall;
  EXPECT_TRUE(fs::exists(tree.results() / past[3] / "luminance.exr"));
}

// Below the reserve the same tiers go, for the disk's sake.
TEST_F(RetentionTiersTest, TheReserveTakesTheSameTiers) {
  const RetentionContext below{.now = utcAt(kToday),
                               .disk = DiskState{.free_bytes = 0, .total_bytes = 100 * kMiB},
                               .reserve_bytes = 6 * (100 * kKiB + 30) + 2 * 3 * 20 * kKiB};
  const RetentionSummary summary = applyRetention(tree, {.max_use_bytes = 1ull << 40}, below);
  EXPECT_EQ(deletedOf(summary, kDeletedStack).size(), 6u);
  EXPECT_EQ(deletedOf(summary, kDeletedResultImages),
            (std::vector<std::string>(past.begin(), past.begin() + 2)));
  EXPECT_TRUE(summary.shortfall.empty()) << summary.shortfall;
  EXPECT_NE(summary.deleted.back().reason.find("below the"), std::string::npos);
}

// A day rebuilt after retention deleted some of its results whole (a late stack of that day
// processed at the next start) keeps their rows and ladders: the table is never poorer.
TEST_F(RetentionTiersTest, ADayRebuiltAfterItsResultsWentKeepsTheirRows) {
  const fs::path day = tree.days() / "2026-06-20";
  const std::string table_before = testing::readText(day / pipeline::kSweepTableFileName);
  const std::string contours_before = testing::readText(day / pipeline::kContourTableFileName);
  applyRetention(tree, {.max_use_bytes = 1}, {.now = utcAt(kToday)});
  ASSERT_FALSE(fs::exists(tree.results() / past[0]));
  const DayProductsOptions options{.root = tree.root(), .longitude_deg = std::nullopt};
  ASSERT_TRUE(updateDayProducts(options, "2026-06-20"));
  EXPECT_EQ(testing::readText(day / pipeline::kSweepTableFileName), table_before);
  EXPECT_EQ(testing::readText(day / pipeline::kContourTableFileName), contours_before);
  // A late stack of that day, processed now: its row joins the kept ones.
  makeGlarecamResult(tree.results() / "20260620T120000Z-a30.00", 50000, 30.0);
  ASSERT_TRUE(updateDayProducts(options, "2026-06-20"));
  EXPECT_EQ(tableIds(tree, "2026-06-20"),
            (std::vector<std::string>{past[0], past[1], "20260620T120000Z-a30.00"}));
}

// A pruned result reads as before: its numbers, the day's rows, the status' brief.
TEST_F(RetentionTiersTest, APrunedResultReadsAsBeforeAndSaysSo) {
  const fs::path day = tree.days() / "2026-06-21";
  const std::string table_before = testing::readText(day / pipeline::kSweepTableFileName);
  const auto before = pipeline::readResult(tree.results() / past[2] / pipeline::kResultFileName);
  ASSERT_TRUE(before);
  const auto pruned = pruneResultImages(tree.results() / past[2], utcAt(kToday));
  ASSERT_TRUE(pruned) << pruned.error().message;
  EXPECT_EQ(pruned->bytes, 3 * 20 * kKiB);
  EXPECT_TRUE(pruned->errors.empty());
  const auto after = pipeline::readResult(tree.results() / past[2] / pipeline::kResultFileName);
  ASSERT_TRUE(after) << after.error().message;
  EXPECT_TRUE(after->outputs.pruned());
  pipeline::StackResult unpruned = *after;
  unpruned.outputs.pruned_at.reset();
  EXPECT_EQ(unpruned, *before);  // nothing else changed
  EXPECT_EQ(entryNames(tree.results() / past[2]),
            std::vector<std::string>{pipeline::kResultFileName});
  // Pruning again changes nothing and frees nothing.
  EXPECT_EQ(pruneResultImages(tree.results() / past[2], utcAt(kToday)).value().bytes, 0u);
  const DayProductsOptions options{.root = tree.root(), .longitude_deg = std::nullopt};
  ASSERT_TRUE(updateDayProducts(options, "2026-06-21"));
  EXPECT_EQ(testing::readText(day / pipeline::kSweepTableFileName), table_before);
  // Not a result, or not glarecam's: nothing is touched.
  fs::create_directories(tree.results() / "20260601T080000Z-x");
  writeText(tree.results() / "20260601T080000Z-x" / "result.json", R"({"schema": "other"})");
  writeText(tree.results() / "20260601T080000Z-x" / "luminance.png", "theirs");
  EXPECT_FALSE(pruneResultImages(tree.results() / "20260601T080000Z-x", utcAt(kToday)));
  EXPECT_TRUE(fs::exists(tree.results() / "20260601T080000Z-x" / "luminance.png"));
}

// Only the files result.json names go, and only inside the result's directory.
TEST_F(RetentionTest, APruneRemovesOnlyTheImagesTheResultNames) {
  const fs::path result = tree.results() / "20260620T080000Z-a40.00";
  makeGlarecamResult(result, 1000, 40.0);
  pipeline::StackResult document = pipeline::readResult(result / pipeline::kResultFileName).value();
  document.outputs.quality_exr = "../outside.exr";  // never followed out of the directory
  writeText(result / pipeline::kResultFileName, jsonText(pipeline::toJson(document)));
  writeText(tree.results() / "outside.exr", "not the result's");
  writeText(result / "operator-notes.txt", "not named");
  ASSERT_TRUE(pruneResultImages(result, utcAt("2026-06-25T12:00:00Z")));
  EXPECT_TRUE(fs::exists(tree.results() / "outside.exr"));
  EXPECT_TRUE(fs::exists(result / "operator-notes.txt"));
  EXPECT_TRUE(fs::exists(result / "quality.exr"));  // not named any more
  EXPECT_FALSE(fs::exists(result / "luminance.exr"));
}

// A power cut in the middle of a prune: before result.json is rewritten nothing has changed;
// after, the result says "pruned" while some images are still there, and the next start finishes
// it. Never a result.json that names a missing image without saying so.
TEST_F(RetentionTest, APruneCutShortIsConsistentAndTheNextStartFinishesIt) {
  const UtcTime now = utcAt("2026-06-25T12:00:00Z");
  const fs::path cut_after_mark = tree.results() / "20260620T080000Z-a40.00";
  const fs::path cut_mid_way = tree.results() / "20260620T090000Z-a40.00";
  const fs::path untouched = tree.results() / "20260620T100000Z-a40.00";
  for (const fs::path& result : {cut_after_mark, cut_mid_way, untouched})
    makeGlarecamResult(result, 1000, 40.0);
  for (const fs::path& result : {cut_after_mark, cut_mid_way}) {
    pipeline::StackResult document =
        pipeline::readResult(result / pipeline::kResultFileName).value();
    document.outputs.pruned_at = formatIsoTime(now);
    ASSERT_TRUE(
        writeFileAtomic(result / pipeline::kResultFileName, jsonText(pipeline::toJson(document))));
  }
  fs::remove(cut_mid_way / "luminance.exr");
  // A staging file of the rewrite the cut interrupted: the next start's leftovers.
  writeText(untouched / ".tmp-result.json-123", "{");

  const auto consistent = [](const fs::path& result) {
    const auto read = pipeline::readResult(result / pipeline::kResultFileName);
    if (!read) return false;
    if (read->outputs.pruned()) return true;
    return std::ranges::all_of(read->outputs.files(),
                               [&](const std::string& f) { return fs::exists(result / f); });
  };
  for (const fs::path& result : {cut_after_mark, cut_mid_way, untouched})
    EXPECT_TRUE(consistent(result)) << result;

  const RetentionSummary finished = finishCutShortPrunes(tree, now);
  EXPECT_EQ(deletedOf(finished, kDeletedResultImages),
            (std::vector<std::string>{"20260620T080000Z-a40.00", "20260620T090000Z-a40.00"}));
  EXPECT_EQ(finished.freed_bytes, 3 * 500u + 2 * 500u);
  EXPECT_EQ(entryNames(cut_after_mark), std::vector<std::string>{"result.json"});
  EXPECT_EQ(entryNames(cut_mid_way), std::vector<std::string>{"result.json"});
  EXPECT_TRUE(fs::exists(untouched / "luminance.exr"));  // never marked: left whole
  EXPECT_EQ(tree.removeLeftovers(), 1u);
  for (const fs::path& result : {cut_after_mark, cut_mid_way, untouched})
    EXPECT_TRUE(consistent(result)) << result;
  EXPECT_TRUE(finishCutShortPrunes(tree, now).deleted.empty());  // nothing left to finish
}

// Today alone over the budget: nothing may go, and the shortfall says the budget is smaller than
// one day's stacks, with how many a day fit.
TEST_F(RetentionTest, TodayAloneOverTheBudgetSaysHowManyStacksADayFit) {
  for (const char* id : {"20260625T080000Z-a40.00", "20260625T090000Z-a30.00",
                         "20260625T100000Z-a20.00", "20260625T110000Z-a10.00"})
    makeProcessed(tree, id, kMiB);
  // 4 stacks of a little over 1 MiB each with their results; 2.5 MiB fit 2 of them.
  const RetentionSummary summary =
      applyRetention(tree, {.max_use_bytes = 5 * kMiB / 2}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_TRUE(summary.deleted.empty());
  EXPECT_TRUE(summary.day_overflows);
  EXPECT_NE(summary.shortfall.find("the budget is smaller than one day's stacks: today's 4 stacks"),
            std::string::npos)
      << summary.shortfall;
  EXPECT_NE(summary.shortfall.find("about 2 stacks a day fit"), std::string::npos)
      << summary.shortfall;
}

// Today would fit in the budget alone, but what past days must keep (here stacks not processed
// yet) leaves it too little: the shortfall says so, not that the budget is smaller than a day.
TEST_F(RetentionTest, WhatThePastKeepsIsNamedWhenTodayWouldFitAlone) {
  makeGlarecamStack(tree.stacks() / "20260623T080000Z-a40.00", 2 * kMiB);  // unprocessed
  makeProcessed(tree, "20260625T080000Z-a40.00", kMiB);
  const RetentionSummary summary =
      applyRetention(tree, {.max_use_bytes = 5 * kMiB / 2}, {.now = utcAt("2026-06-25T12:00:00Z")});
  EXPECT_FALSE(summary.day_overflows);
  EXPECT_NE(summary.shortfall.find("stacks kept: 1 unprocessed, 1 of today"), std::string::npos)
      << summary.shortfall;
  EXPECT_NE(summary.shortfall.find("what past days keep (2.0 MiB) leaves 512.0 KiB for today's 1 "
                                   "stacks"),
            std::string::npos)
      << summary.shortfall;
  EXPECT_NE(summary.shortfall.find("about 0 stacks a day fit"), std::string::npos)
      << summary.shortfall;
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
