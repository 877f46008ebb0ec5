// glarecam sweep's library: finding stacks, processing them in parallel, skipping bad ones.
#include "pipeline/sweep.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>

#include "core/image_io.h"
#include "core/parallel.h"
#include "pipeline/contour_table.h"
#include "pipeline/process_stack.h"
#include "pipeline/result.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

void writeStackAt(const fs::path& directory, double alpha_deg) {
  testing::writeSmallStack(directory, testing::smallScene(alpha_deg));
}

void removeAlpha(const fs::path& stack) {
  auto manifest = nlohmann::json::parse(testing::readText(stack / "stack.json"));
  manifest.erase("alpha_deg");
  testing::writeText(stack / "stack.json", manifest.dump());
}

SweepOptions quiet(const fs::path& out, unsigned jobs) {
  SweepOptions options;
  options.output_directory = out;
  options.jobs = jobs;
  options.show_progress = false;
  return options;
}

// The threads this process runs now, its own included (Linux: one entry each in /proc/self/task).
long runningThreads() {
  long count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator("/proc/self/task")) ++count;
  return count;
}

// --threads 1 means one thread in every stage of process and sweep: none of ours started
// (threadsStarted()), and none of a library's left running (OpenEXR's pool would stay). In a
// fresh process ("threadsafe" death tests re-run the test binary), whose every step is under the
// budget, so that nothing has made a pool before. Threads that run from the start (LTTng's, which
// a linked library brings) are counted before and after.
TEST(SweepDeathTest, OneThreadMeansOneInProcessAndSweep) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const ThreadBudget one(1);
        TempDir dir;
        writeStackAt(dir / "stacks/a", 30);
        writeStackAt(dir / "stacks/b", 50);
        const std::uint64_t before = threadsStarted();
        const long running_before = runningThreads();
        ProcessOptions process;
        process.show_progress = false;
        process.threads = 1;
        process.output_directory = dir / "one";
        const bool processed = processStack(dir / "stacks/a", process).has_value();
        SweepOptions sweep = quiet(dir / "out", 0);
        sweep.threads = 1;
        const bool swept = runSweep(findStacks({dir / "stacks"}), sweep).has_value();
        std::fprintf(stderr, "processed %d swept %d threads started %llu, more running %ld\n",
                     processed, swept, static_cast<unsigned long long>(threadsStarted() - before),
                     runningThreads() - running_before);
        std::exit(0);
      },
      ::testing::ExitedWithCode(0), "processed 1 swept 1 threads started 0, more running 0");
}

// No more jobs run than fit in the memory budget: the estimate follows the stack's frames (size
// from the header, count from the manifest), and a budget below two stacks runs one at a time.
TEST(RunSweep, RunsNoMoreJobsThanFitInTheMemoryBudget) {
  TempDir dir;
  writeStackAt(dir / "stacks/a", 30);
  writeStackAt(dir / "stacks/b", 50);
  const auto manifest = nlohmann::json::parse(testing::readText(dir / "stacks/a/stack.json"));
  const std::uint64_t frames = manifest["frames"].size();
  const RawFrame first =
      readRawFrame(dir / "stacks/a" / manifest["frames"][0]["file"].get<std::string>())->pixels;
  const std::optional<std::uint64_t> bytes = processMemoryBytes(dir / "stacks/a");
  ASSERT_TRUE(bytes);
  EXPECT_EQ(*bytes, first.pixelCount() * (52 + 2 * frames));  // sweep.cpp's per-pixel figures
  EXPECT_FALSE(processMemoryBytes(dir / "missing"));

  SweepOptions options = quiet(dir / "out", 2);
  options.threads = 2;
  options.memory_budget_bytes = 2 * *bytes;
  auto both = runSweep(findStacks({dir / "stacks"}), options);
  ASSERT_TRUE(both) << both.error().message;
  EXPECT_EQ(both->jobs, 2u);
  EXPECT_EQ(both->stack_memory_bytes, *bytes);
  options.memory_budget_bytes = 2 * *bytes - 1;
  auto one = runSweep(findStacks({dir / "stacks"}), options);
  ASSERT_TRUE(one) << one.error().message;
  EXPECT_EQ(one->jobs, 1u);
  EXPECT_EQ(one->table.rows.size(), 2u);
  options.memory_budget_bytes = 1;  // even then one job runs
  auto tiny = runSweep(findStacks({dir / "stacks"}), options);
  ASSERT_TRUE(tiny) << tiny.error().message;
  EXPECT_EQ(tiny->jobs, 1u);
}

TEST(FindStacks, StacksDirectoriesOfStacksAndWhatIsNeither) {
  TempDir dir;
  writeStackAt(dir / "stacks/b", 20);
  writeStackAt(dir / "stacks/a", 40);
  fs::create_directories(dir / "stacks/not-a-stack");
  writeStackAt(dir / "single", 60);
  fs::create_directories(dir / "empty");
  const StackSearch search =
      findStacks({dir / "stacks", dir / "single", dir / "empty", dir / "missing"});
  ASSERT_EQ(search.stacks.size(), 3u);
  EXPECT_EQ(search.stacks[0], dir / "stacks/a");  // sorted within a directory
  EXPECT_EQ(search.stacks[2], dir / "single");
  ASSERT_EQ(search.skipped.size(), 2u);
  EXPECT_EQ(search.skipped[0].stack, dir / "empty");
  EXPECT_EQ(search.skipped[1].error.code, ErrorCode::kBadInput);
}

TEST(Sweep, ProcessesGoodStacksSortedByAlphaAndReportsBadOnes) {
  TempDir dir;
  writeStackAt(dir / "stacks/s1", 60);
  writeStackAt(dir / "stacks/s2", 20);
  writeStackAt(dir / "stacks/s3", 40);
  writeStackAt(dir / "stacks/no-alpha", 30);
  removeAlpha(dir / "stacks/no-alpha");
  fs::create_directories(dir / "stacks/broken");
  testing::writeText(dir / "stacks/broken/stack.json", "{ not json");

  auto summary = runSweep(findStacks({dir / "stacks"}), quiet(dir / "out", 2));
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->skipped.size(), 2u);
  const std::string csv = testing::readText(dir / "out/sweep.csv");
  EXPECT_NE(csv.find("# skipped " + (dir / "stacks/broken").string()), std::string::npos) << csv;
  EXPECT_NE(csv.find("alpha_deg is missing"), std::string::npos) << csv;
  auto table = readSweepTable(dir / "out/sweep.csv");
  ASSERT_TRUE(table) << table.error().message;
  ASSERT_EQ(table->rows.size(), 3u);
  EXPECT_EQ(table->rows[0].alpha_deg, 20);
  EXPECT_EQ(table->rows[2].alpha_deg, 60);
  EXPECT_TRUE(table->rows[0].vertical_deg);
  EXPECT_EQ(table->rows[0].stack, (dir / "stacks/s2").string());
  EXPECT_TRUE(fs::exists(dir / "out/results/s2/result.json"));
  EXPECT_TRUE(fs::exists(dir / "out/results/s2/luminance.png"));
  // contours.csv beside it: each processed stack's ladder, row for row its result's contours.
  EXPECT_EQ(summary->contours_csv, dir / "out/contours.csv");
  auto contours = readContourTable(dir / "out/contours.csv");
  ASSERT_TRUE(contours) << contours.error().message;
  std::vector<ContourRow> expected;
  for (const char* stack : {"s2", "s3", "s1"}) {  // by α
    auto result = readResult(dir / "out/results" / stack / "result.json");
    ASSERT_TRUE(result) << result.error().message;
    ASSERT_TRUE(result->contours);
    EXPECT_GE(result->contours->size(), 3u) << stack;  // fixed rungs, the limit, the half maximum
    for (const ContourRow& row : contourRowsFromResult(*result)) expected.push_back(row);
  }
  EXPECT_EQ(contours->rows, expected);
  EXPECT_EQ(contours->rows.front().alpha_deg, 20);
  EXPECT_EQ(contours->rows.front().kind, ContourKind::kLadder);
  EXPECT_EQ(contours->rows.front().level_cd_m2, 1e4);
}

// One table is one module measured with one camera and calibration: stacks whose calibrations
// differ are refused, naming what differs, and no table is written; --mixed writes it with a note.
// Each row records what it was measured with.
TEST(Sweep, StacksOfDifferentCalibrationsAreNotMixedUnlessAsked) {
  TempDir dir;
  writeStackAt(dir / "stacks/s1", 20);
  writeStackAt(dir / "stacks/s2", 40);
  writeStackAt(dir / "stacks/s3", 60);
  auto manifest = nlohmann::json::parse(testing::readText(dir / "stacks/s3/stack.json"));
  manifest["calibration"]["luminance_factor"] =
      2 * manifest["calibration"]["luminance_factor"].get<double>();
  testing::writeText(dir / "stacks/s3/stack.json", manifest.dump());

  auto refused = runSweep(findStacks({dir / "stacks"}), quiet(dir / "out", 2));
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  EXPECT_NE(refused.error().message.find("the stacks differ in calibration ("), std::string::npos)
      << refused.error().message;
  EXPECT_EQ(refused.error().message.find("camera ("), std::string::npos);  // one camera
  EXPECT_FALSE(fs::exists(dir / "out/sweep.csv"));

  SweepOptions mixed = quiet(dir / "out", 2);
  mixed.allow_mixed = true;
  auto summary = runSweep(findStacks({dir / "stacks"}), mixed);
  ASSERT_TRUE(summary) << summary.error().message;
  auto table = readSweepTable(dir / "out/sweep.csv");
  ASSERT_TRUE(table) << table.error().message;
  ASSERT_EQ(table->notes.size(), 1u);
  EXPECT_EQ(table->notes[0].rfind("mixed: the stacks differ in calibration (", 0), 0u);
  const SweepRow& row = table->rows[0];
  EXPECT_EQ(row.camera_backend, "sim");
  EXPECT_FALSE(row.camera_serial.empty());
  EXPECT_TRUE(row.width && row.height);
  EXPECT_EQ(row.calibration_id.size(), 16u);
  EXPECT_EQ(table->rows[1].calibration_id, row.calibration_id);
  EXPECT_NE(table->rows[2].calibration_id, row.calibration_id);
  EXPECT_NE(mixedFields(*table).find("calibration"), std::string::npos);
  table->rows.pop_back();
  EXPECT_EQ(mixedFields(*table), "");
  table->rows[1].width = 2 * *row.width;
  table->rows[1].camera_serial = "40012345";
  EXPECT_EQ(mixedFields(*table).rfind("camera (", 0), 0u) << mixedFields(*table);
  EXPECT_NE(mixedFields(*table).find("frame size ("), std::string::npos);
  // Each simulated stack names its module; another module's row is mixing, named first.
  EXPECT_EQ(row.module, "simulated standard module");
  table->rows[1].module = "ACME 400 #17";
  EXPECT_EQ(mixedFields(*table).rfind("module (simulated standard module, ACME 400 #17)", 0), 0u)
      << mixedFields(*table);
}

// sweep --alpha-from gives α to stacks that record none, by directory name, recorded as given;
// one that contradicts a stack's own α skips that stack; the table's bad lines are named.
TEST(Sweep, AlphaFromATableForStacksThatRecordNone) {
  TempDir dir;
  writeStackAt(dir / "stacks/s1", 20);
  writeStackAt(dir / "stacks/s2", 40);
  writeStackAt(dir / "stacks/s3", 60);
  removeAlpha(dir / "stacks/s1");
  removeAlpha(dir / "stacks/s2");
  testing::writeText(dir / "alpha.csv",
                     "# measured by hand\nstack,alpha_deg,note\ns1,20,x\ns2,40,\ns3,65,\n");
  auto given = readAlphaTable(dir / "alpha.csv");
  ASSERT_TRUE(given) << given.error().message;
  EXPECT_EQ(given->at("s2"), 40);
  // A spreadsheet's export (byte-order mark, CRLF) reads the same (core/csv.h's reader).
  testing::writeText(dir / "exported.csv", "\xEF\xBB\xBFstack,alpha_deg\r\ns1,20\r\ns2,40\r\n");
  auto exported = readAlphaTable(dir / "exported.csv");
  ASSERT_TRUE(exported) << exported.error().message;
  EXPECT_EQ(exported->at("s2"), 40);
  SweepOptions options = quiet(dir / "out", 2);
  options.given_alpha_deg = *given;
  auto summary = runSweep(findStacks({dir / "stacks"}), options);
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_EQ(summary->table.rows.size(), 2u);
  EXPECT_EQ(summary->table.rows[0].alpha_deg, 20);
  ASSERT_EQ(summary->skipped.size(), 1u);  // s3 records 60: the table's 65 contradicts it
  EXPECT_NE(summary->skipped[0].error.message.find("contradicts"), std::string::npos);
  const auto result = nlohmann::json::parse(testing::readText(dir / "out/results/s1/result.json"));
  EXPECT_EQ(result["alpha_source"], "given");

  const std::pair<std::string, std::string> bad[] = {
      {"alpha_deg\n20\n", "alpha.csv:1: the header must name the columns stack and alpha_deg"},
      {"stack,alpha_deg\ns1,steep\n", "alpha.csv:2: expected a stack name and a number"},
      {"stack,alpha_deg\ns1,95\n", "alpha.csv:2: alpha_deg 95 is outside"},
      {"stack,alpha_deg\ns1,20\ns1,21\n", "alpha.csv:3: stack s1 is given twice"},
      {"", "empty α table"},
      {"stack,alpha_deg\n\"s1,20\n", "alpha.csv:2: "}};
  for (const auto& [text, message] : bad) {
    testing::writeText(dir / "alpha.csv", text);
    auto refused = readAlphaTable(dir / "alpha.csv");
    ASSERT_FALSE(refused) << text;
    EXPECT_NE(refused.error().message.find(message), std::string::npos) << refused.error().message;
  }
}

TEST(Sweep, OneJobAndManyJobsGiveTheSameTable) {
  TempDir dir;
  for (double alpha : {10.0, 50.0, 70.0})
    writeStackAt(dir / ("stacks/a" + std::to_string(int(alpha))), alpha);
  auto one = runSweep(findStacks({dir / "stacks"}), quiet(dir / "one", 1));
  auto many = runSweep(findStacks({dir / "stacks"}), quiet(dir / "many", 3));
  ASSERT_TRUE(one && many);
  EXPECT_EQ(testing::readText(dir / "one/sweep.csv"), testing::readText(dir / "many/sweep.csv"));
}

TEST(Sweep, SameStackNameTwiceGetsTwoResultDirectories) {
  TempDir dir;
  writeStackAt(dir / "day1/alpha", 20);
  writeStackAt(dir / "day2/alpha", 40);
  auto summary =
      runSweep(findStacks({dir / "day1/alpha", dir / "day2/alpha"}), quiet(dir / "o", 2));
  ASSERT_TRUE(summary);
  EXPECT_TRUE(fs::exists(dir / "o/results/alpha/result.json"));
  EXPECT_TRUE(fs::exists(dir / "o/results/alpha-2/result.json"));
}

TEST(FindStacks, TrailingSlashesAndTheSameStackTwice) {
  TempDir dir;
  writeStackAt(dir / "s1", 20);
  const StackSearch search =
      findStacks({fs::path((dir / "s1").string() + "/"), dir / "./s1", dir.path()});
  ASSERT_EQ(search.stacks.size(), 1u);
  EXPECT_EQ(search.stacks[0].filename(), "s1");
}

TEST(Sweep, AStackAtGrazingIncidenceIsSkippedBeforeProcessing) {
  TempDir dir;
  writeStackAt(dir / "stacks/ok", 40);
  writeStackAt(dir / "stacks/grazing", 40);
  auto manifest = nlohmann::json::parse(testing::readText(dir / "stacks/grazing/stack.json"));
  manifest["alpha_deg"] = 90.0;
  testing::writeText(dir / "stacks/grazing/stack.json", manifest.dump());
  auto summary = runSweep(findStacks({dir / "stacks"}), quiet(dir / "out", 1));
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_EQ(summary->skipped.size(), 1u);
  EXPECT_NE(summary->skipped[0].error.message.find("outside [0, 90)"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out/results/grazing"));  // refused before processing
}

TEST(Sweep, ResultNamesNeverCollide) {
  // Two stacks named s1 and one named s1-2: the second s1 must not take s1-2's name.
  TempDir dir;
  writeStackAt(dir / "x/s1", 20);
  writeStackAt(dir / "y/s1", 40);
  writeStackAt(dir / "z/s1-2", 60);
  auto summary =
      runSweep(findStacks({dir / "x/s1", dir / "y/s1", dir / "z/s1-2"}), quiet(dir / "o", 2));
  ASSERT_TRUE(summary) << summary.error().message;
  std::set<double> alphas;
  for (const char* name : {"s1", "s1-2", "s1-3"}) {
    auto result =
        nlohmann::json::parse(testing::readText(dir / "o/results" / name / "result.json"));
    alphas.insert(result["alpha_deg"].get<double>());
  }
  EXPECT_EQ(alphas, (std::set<double>{20, 40, 60}));
  EXPECT_EQ(
      nlohmann::json::parse(testing::readText(dir / "o/results/s1-2/result.json"))["alpha_deg"],
      60.0);
}

TEST(Sweep, AnOutputPathThatIsAFileIsBadInputBeforeAnyWork) {
  TempDir dir;
  writeStackAt(dir / "s", 20);
  testing::writeText(dir / "file", "x");
  auto summary = runSweep(findStacks({dir / "s"}), quiet(dir / "file", 1));
  ASSERT_FALSE(summary);
  EXPECT_EQ(summary.error().code, ErrorCode::kBadInput);
  EXPECT_FALSE(fs::exists(dir / "s/result"));
}

TEST(Sweep, NothingProcessableIsBadInput) {
  TempDir dir;
  fs::create_directories(dir / "broken");
  testing::writeText(dir / "broken/stack.json", "[]");
  auto summary = runSweep(findStacks({dir / "broken", dir / "missing"}), quiet(dir / "o", 1));
  ASSERT_FALSE(summary);
  EXPECT_EQ(summary.error().code, ErrorCode::kBadInput);
  EXPECT_NE(summary.error().message.find("no stack could be processed"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "o/sweep.csv"));
}

}  // namespace
}  // namespace glarecam::pipeline
