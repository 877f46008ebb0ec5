// The sweep table CSV (docs/stack-format.md): reading, validation with file:line errors, writing.
#include "pipeline/sweep_table.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>

#include "support/test_support.h"
#include "tests/pipeline/result_fixture.h"

namespace glarecam::pipeline {
namespace {

using testing::TempDir;
using testing::writeText;

constexpr const char* kHeader = "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg\n";

Result<SweepTable> readText(const TempDir& dir, const std::string& text) {
  writeText(dir / "sweep.csv", text);
  return readSweepTable(dir / "sweep.csv");
}

TEST(SweepTable, ReadsThePapersTableIII) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table) << table.error().message;
  ASSERT_EQ(table->rows.size(), 9u);
  EXPECT_EQ(table->rows[6].alpha_deg, 60);
  EXPECT_EQ(table->rows[6].limit_cd_m2, 40000);
  EXPECT_EQ(table->rows[6].lmax_cd_m2, 2400000);
  EXPECT_EQ(table->rows[8].horizontal_deg, 2.3);
}

TEST(SweepTable, ColumnsInAnyOrderCommentsEmptyAxesAndQuotes) {
  TempDir dir;
  auto table = readText(dir,
                        "# a comment\n"
                        "note,horizontal_deg,vertical_deg,lmax_cd_m2,limit_cd_m2,alpha_deg\n"
                        "\"a, quoted \"\"note\"\"\",5.5,4.5,600000,30000,10\n"
                        "x,,,20000,30000,20\n");
  ASSERT_TRUE(table) << table.error().message;
  ASSERT_EQ(table->rows.size(), 2u);
  EXPECT_EQ(table->notes, std::vector<std::string>{"a comment"});
  EXPECT_EQ(table->rows[0].horizontal_deg, 5.5);
  EXPECT_FALSE(table->rows[1].vertical_deg);
}

TEST(SweepTable, SpreadsheetExportsWithAByteOrderMarkAndCrlfRead) {
  TempDir dir;
  // The header's line ending made CRLF (kHeader ends in '\n'); built by appending, as GCC 12 at
  // -O3 warns about a string::insert here (-Wstringop-overflow, a false positive).
  std::string header(kHeader, std::strlen(kHeader) - 1);
  header += "\r\n";
  auto table = readText(dir, "\xEF\xBB\xBF" + header + "5,30000,594000,5.0,5.7\r\n");
  ASSERT_TRUE(table) << table.error().message;
  EXPECT_EQ(table->rows.at(0).horizontal_deg, 5.7);
}

TEST(SweepTable, WritesSortedAndReadsBackWhatItWrote) {
  SweepTable table;
  table.notes = {"skipped x: broken"};
  SweepRow flat, steep;
  flat.alpha_deg = 70;
  flat.limit_cd_m2 = 1e5;
  flat.lmax_cd_m2 = 1.19e7;
  flat.vertical_deg = 8.2;
  flat.horizontal_deg = 3.6;
  steep.alpha_deg = 5;
  steep.limit_cd_m2 = 3e4;
  steep.lmax_cd_m2 = 20000;
  steep.stack = "dir, with comma/alpha-05";
  steep.glare = false;
  table.rows = {flat, steep};
  SweepTable with_break = table;
  with_break.notes = {"skipped a\nb: broken"};
  with_break.rows[1].stack = "day\n1/alpha-05";
  TempDir dir;
  auto read = readText(dir, formatSweepTable(table));
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->rows.size(), 2u);
  EXPECT_EQ(read->rows[0].alpha_deg, 5);
  EXPECT_EQ(read->rows[0].stack, "dir, with comma/alpha-05");
  EXPECT_EQ(read->rows[0].glare, false);
  EXPECT_FALSE(read->rows[0].vertical_deg);
  EXPECT_EQ(read->rows[1].lmax_cd_m2, 1.19e7);
  EXPECT_EQ(read->notes, table.notes);
  // A line break in a note (a stack path may hold one) stays inside the comment.
  auto broken = readText(dir, formatSweepTable(with_break));
  ASSERT_TRUE(broken) << broken.error().message;
  EXPECT_EQ(broken->notes, std::vector<std::string>{"skipped a b: broken"});
  EXPECT_EQ(broken->rows.at(0).stack, "day 1/alpha-05");
}

struct BadCsv {
  const char* name;
  std::string text;
  const char* message;  // part of the expected error
};

void PrintTo(const BadCsv& c, std::ostream* out) { *out << c.name; }

class SweepTableBadInput : public ::testing::TestWithParam<BadCsv> {};

TEST_P(SweepTableBadInput, IsAOneLineErrorNamingFileAndProblem) {
  TempDir dir;
  auto table = readText(dir, GetParam().text);
  ASSERT_FALSE(table);
  EXPECT_EQ(table.error().code, ErrorCode::kBadInput);
  EXPECT_NE(table.error().message.find("sweep.csv"), std::string::npos) << table.error().message;
  EXPECT_NE(table.error().message.find(GetParam().message), std::string::npos)
      << table.error().message;
  EXPECT_EQ(table.error().message.find('\n'), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SweepTableBadInput,
    ::testing::Values(
        BadCsv{"Empty", "", "no header"}, BadCsv{"HeaderOnly", kHeader, "no rows"},
        BadCsv{"MissingColumn", "alpha_deg,lmax_cd_m2\n5,1\n", "missing column(s) limit_cd_m2"},
        BadCsv{"NonNumeric", std::string(kHeader) + "5,30000,lots,5,5\n", "sweep.csv:2: lmax"},
        BadCsv{"NotFinite", std::string(kHeader) + "5,30000,inf,5,5\n", "not a finite number"},
        BadCsv{"AlphaNegative", std::string(kHeader) + "-1,30000,5e5,5,5\n", "outside [0, 90)"},
        BadCsv{"AlphaNinety", std::string(kHeader) + "90,30000,5e5,5,5\n", "outside [0, 90)"},
        BadCsv{"LmaxEmpty", std::string(kHeader) + "5,30000,,5,5\n", "lmax_cd_m2 is empty"},
        BadCsv{"LmaxZero", std::string(kHeader) + "5,30000,0,5,5\n", "must be positive"},
        BadCsv{"AxisNegative", std::string(kHeader) + "5,30000,5e5,-5,5\n", "must be positive"},
        BadCsv{"Unterminated", std::string(kHeader) + "5,30000,5e5,5,\"5\n", "unterminated"},
        BadCsv{"TrailingGarbage", std::string(kHeader) + "5,30000,5e5x,5,5\n", "5e5x"},
        BadCsv{"DuplicateColumn", std::string("alpha_deg,") + kHeader + "5,6,30000,5e5,5,5\n",
               "column alpha_deg appears twice"},
        BadCsv{"AxisBeyondPhysical", std::string(kHeader) + "5,30000,5e5,500,5\n",
               "beyond the physical range"},
        BadCsv{"LmaxBeyondPhysical", std::string(kHeader) + "5,30000,1e300,5,5\n",
               "beyond the physical range"},
        BadCsv{"Semicolons", "alpha_deg;limit_cd_m2;lmax_cd_m2;vertical_deg;horizontal_deg\n",
               "comma-separated"},
        BadCsv{"KZero",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
               "luminance_factor\n5,30000,5e5,5,5,0\n",
               "luminance_factor: 0 must be positive"},
        BadCsv{"KUncertaintyNegative",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,"
               "horizontal_deg,luminance_factor_u\n5,30000,5e5,5,5,-1\n",
               "luminance_factor_u: -1 must not be negative"},
        BadCsv{"SourceOriginUnknown",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,source_origin\n"
               "5,30000,5e5,5,5,moon\n",
               "source_origin: \"moon\" is not sensor, given, clear_sky or unreferred"},
        BadCsv{"ReferredWithoutReference",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
               "source_illuminance_lx,source_origin\n5,30000,5e5,5,5,90000,sensor\n",
               "needs source_illuminance_lx and reference_illuminance_lx"},
        BadCsv{"UnreferredWithIlluminance",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
               "source_illuminance_lx,source_origin\n5,30000,5e5,5,5,90000,unreferred\n",
               "an unreferred row has no source_illuminance_lx"},
        BadCsv{"IlluminanceInWattsPerSquareMetre",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
               "source_illuminance_lx,source_origin,reference_illuminance_lx\n"
               "5,30000,5e5,5,5,900000,sensor,100000\n",
               "source_illuminance_lx: 900000 is outside (0, 150000] lx"},
        BadCsv{"AlphaUncertaintyZero",
               "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,"
               "horizontal_deg,alpha_uncertainty_deg\n5,30000,5e5,5,5,0\n",
               "alpha_uncertainty_deg: 0 must be positive"}),
    [](const auto& info) { return info.param.name; });

SweepTable limits(std::initializer_list<std::pair<double, double>> alpha_limit) {
  SweepTable table;
  for (const auto& [alpha, limit] : alpha_limit) {
    SweepRow row;
    row.alpha_deg = alpha;
    row.limit_cd_m2 = limit;
    row.lmax_cd_m2 = 1e6;
    table.rows.push_back(row);
  }
  return table;
}

TEST(SweepTable, InfersTheLimitTheSweepUsed) {
  std::string warning;
  EXPECT_FALSE(inferGlareLimit(limits({{5, 3e4}, {60, 4e4}, {80, 4e5}}), &warning).constant_cd_m2);
  EXPECT_EQ(inferGlareLimit(limits({{5, 3e4}, {60, 3e4}, {80, 3e4}})).constant_cd_m2, 3e4);
  EXPECT_TRUE(warning.empty());
  EXPECT_FALSE(inferGlareLimit(limits({{5, 3e4}, {60, 5e4}, {80, 3e4}}), &warning).constant_cd_m2);
  EXPECT_NE(warning.find("neither the α curve nor one constant"), std::string::npos);
}

TEST(SweepTable, MissingFileOrADirectoryIsBadInput) {
  auto table = readSweepTable("/nonexistent/sweep.csv");
  ASSERT_FALSE(table);
  EXPECT_EQ(table.error().code, ErrorCode::kBadInput);
  TempDir dir;
  table = readSweepTable(dir.path());
  ASSERT_FALSE(table);
  EXPECT_EQ(table.error().code, ErrorCode::kBadInput);
  EXPECT_NE(table.error().message.find("a directory"), std::string::npos);
}

TEST(SweepTable, RowFromAResultNeedsAlpha) {
  StackResult result = testing::minimalResult(5e5);
  EXPECT_FALSE(sweepRowFromResult(result, "s"));
  result.alpha_deg = 30.0;
  result.alpha_source = "manifest";
  ResultEllipse ellipse;
  ellipse.vertical_deg = 4.9;
  ellipse.horizontal_deg = 5.2;
  result.limit = {.limit_cd_m2 = 30000.0,
                  .mode = LimitMode::kAlphaCurve,
                  .status = EllipseStatus::kMeasured,
                  .ellipse = ellipse};
  result.glare = true;
  auto row = sweepRowFromResult(result, "s");
  ASSERT_TRUE(row) << row.error().message;
  EXPECT_EQ(row->vertical_deg, 4.9);
  EXPECT_FALSE(row->fwhm_vertical_deg);
  EXPECT_EQ(row->limit_status, "measured");
  EXPECT_EQ(row->glare, true);
  EXPECT_EQ(row->frames_consistent, std::nullopt);
  EXPECT_FALSE(row->isSuspect());
  result.limit = {};
  EXPECT_EQ(sweepRowFromResult(result, "s")->limit_status, "no_limit");
}

// What each number rests on travels from result.json through sweep.csv: α's uncertainty, the
// calibration's id, the day of its newest part, and K ± u(K); the sheet's one-line summary.
TEST(SweepTable, TheCalibrationAndAlphaUncertaintyTravelThroughTheTable) {
  StackResult result = testing::minimalResult(5e5, 40.0);
  result.alpha_uncertainty_deg = 0.05;
  result.calibration.id = "55e5f09d95ab9da6";
  result.calibration.luminance_factor = 1500.2;
  result.calibration.luminance_factor_u = 18.9;
  result.calibration.parts = {{"dark", {.measured_at = "2026-06-20T10:00:00Z"}},
                              {"luminance", {.measured_at = "2026-06-21T09:30:00Z"}},
                              {"flat", {}}};
  auto row = sweepRowFromResult(result, "stacks/a40");
  ASSERT_TRUE(row) << row.error().message;
  EXPECT_EQ(row->alpha_uncertainty_deg, 0.05);
  EXPECT_EQ(row->calibration_date, "2026-06-21");
  EXPECT_EQ(row->luminance_factor, 1500.2);
  EXPECT_EQ(row->luminance_factor_u, 18.9);
  EXPECT_EQ(calibrationSummary(*row),
            "55e5f09d95ab9da6 of 2026-06-21, K 1500.2 \u00b1 18.9 cd/m\u00b2 per DN/\u00b5s");
  SweepTable table;
  table.rows = {*row};
  TempDir dir;
  auto read = readText(dir, formatSweepTable(table));
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->rows[0].alpha_uncertainty_deg, 0.05);
  EXPECT_EQ(read->rows[0].calibration_date, "2026-06-21");
  EXPECT_EQ(read->rows[0].luminance_factor, 1500.2);
  EXPECT_EQ(read->rows[0].luminance_factor_u, 18.9);
  EXPECT_EQ(tableCalibrationSummaries(*read), std::vector<std::string>{calibrationSummary(*row)});
  // An inline calibration (no parts, no u(K)): the id and K only.
  result.calibration = {.id = "0123456789abcdef", .luminance_factor = 1500.0};
  auto plain = sweepRowFromResult(result, "s");
  ASSERT_TRUE(plain);
  EXPECT_EQ(calibrationSummary(*plain), "0123456789abcdef, K 1500 cd/m\u00b2 per DN/\u00b5s");
}

// A stack whose frames disagree with the merge makes a suspect row, the frames named, and the
// table keeps that through writing and reading.
TEST(SweepTable, FramesThatDisagreeMakeASuspectRow) {
  StackResult result = testing::minimalResult(5e5, 40.0);
  result.luminance.frames_consistent = false;
  result.frames = {{.file = "frame-02.png", .median_ratio = 1.0, .samples = 900, .agrees = true},
                   {.file = "frame-03.png", .median_ratio = 17.1, .samples = 900, .agrees = false},
                   {.file = "frame-04.png"}};
  auto row = sweepRowFromResult(result, "stacks/a40");
  ASSERT_TRUE(row) << row.error().message;
  EXPECT_EQ(row->frames_consistent, false);
  EXPECT_EQ(row->suspect, "frames disagree with the merge: frame-03.png reads 17.1 times");
  result.luminance.frames_consistent = true;
  auto fine = sweepRowFromResult(result, "stacks/a40");
  ASSERT_TRUE(fine);
  EXPECT_FALSE(fine->isSuspect());

  SweepTable table;
  table.rows = {*row, *fine};
  table.rows[1].alpha_deg = 50;
  TempDir dir;
  auto read = readText(dir, formatSweepTable(table));
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->rows[0].frames_consistent, false);
  EXPECT_EQ(read->rows[0].suspect, row->suspect);
  EXPECT_EQ(read->rows[1].frames_consistent, true);
  EXPECT_FALSE(read->rows[1].isSuspect());

  // Written by another tool: frames_consistent false alone still makes the row suspect.
  auto bare = readText(dir,
                       "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
                       "frames_consistent\n40,30000,5e5,4,4,false\n");
  ASSERT_TRUE(bare) << bare.error().message;
  EXPECT_EQ(bare->rows[0].suspect, "frames disagree with the merge");
  auto bad = readText(dir,
                      "alpha_deg,limit_cd_m2,lmax_cd_m2,vertical_deg,horizontal_deg,"
                      "frames_consistent\n40,30000,5e5,4,4,maybe\n");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("frames_consistent: expected true, false or nothing"),
            std::string::npos)
      << bad.error().message;
}

}  // namespace
}  // namespace glarecam::pipeline

namespace glarecam::pipeline {
namespace {

// A result referred from `source_lx` to 100 klx (or unreferred), as a row.
SweepRow referredRow(double alpha_deg, std::optional<double> source_lx, std::string id) {
  StackResult result = testing::minimalResult(5e5, alpha_deg);
  result.stack = std::move(id);
  result.luminance.max_relative_uncertainty = 0.004;
  if (source_lx) {
    result.illuminance.source = SourceIlluminance{.illuminance_lx = *source_lx,
                                                  .illuminance_u_lx = 0.03 * *source_lx,
                                                  .origin = IlluminanceOrigin::kSensor};
    result.illuminance.reference_lx = 100'000;
  }
  auto row = sweepRowFromResult(result, "stacks/" + result.stack);
  EXPECT_TRUE(row) << row.error().message;
  return *row;
}

TEST(SweepTableReferences, TheSourceTravelsThroughTheTable) {
  SweepTable table;
  table.rows = {referredRow(40, 61'200, "a40"), referredRow(20, 98'400, "a20")};
  // A referred row's own uncertainty carries u(E) (3 %) beside the merge's noise (0.4 %).
  EXPECT_NEAR(*table.rows[0].lmax_uncertainty_cd_m2, std::hypot(0.004, 0.03) * 5e5, 1e-6);
  TempDir dir;
  auto read = readText(dir, formatSweepTable(table));
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->rows.size(), 2u);
  EXPECT_EQ(read->rows[1].source_illuminance_lx, 61'200);
  EXPECT_EQ(read->rows[1].source_illuminance_u_lx, 0.03 * 61'200);
  EXPECT_EQ(read->rows[1].source_origin, "sensor");
  EXPECT_EQ(read->rows[1].reference_illuminance_lx, 100'000);
  EXPECT_EQ(mixedReferences(*read), "");
  EXPECT_EQ(tableReferenceIlluminance(*read), 100'000);
  EXPECT_EQ(sourceIlluminanceRange(*read), "61.2\u201398.4 klx (sensor)");
  // Unreferred rows say so in the table, and a table without the columns reads as unreferred.
  SweepTable plain;
  plain.rows = {referredRow(40, std::nullopt, "p40")};
  EXPECT_NE(formatSweepTable(plain).find(",unreferred,"), std::string::npos);
  auto old = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(old);
  EXPECT_EQ(tableReferences(*old), std::vector<std::string>{"unreferred"});
  EXPECT_FALSE(tableReferenceIlluminance(*old));
  EXPECT_EQ(sourceIlluminanceRange(*old), "");
}

TEST(SweepTableReferences, AMixedTableNamesTheRowsOfTheSmallerGroups) {
  SweepTable table;
  for (int alpha = 5; alpha <= 40; alpha += 5)
    table.rows.push_back(referredRow(alpha, 90'000, fmt::format("r{}", alpha)));
  table.rows.push_back(referredRow(45, std::nullopt, "u45"));
  table.rows.push_back(referredRow(50, std::nullopt, "u50"));
  EXPECT_EQ(mixedReferences(table),
            "8 row(s) referred to 100 klx; 2 row(s) unreferred: u45 (\u03b1 45\u00b0), u50 "
            "(\u03b1 50\u00b0)");
  EXPECT_FALSE(tableReferenceIlluminance(table));
  // A rig's day sheet keeps the referred rows (its instrument failed for the others).
  std::string left_out;
  const SweepTable one = rowsOfOneReference(table, &left_out);
  EXPECT_EQ(one.rows.size(), 8u);
  EXPECT_EQ(tableReferenceIlluminance(one), 100'000);
  EXPECT_EQ(left_out.rfind("2 row(s) not referred to 100 klx left out (", 0), 0u) << left_out;
  // Only unreferred rows: all kept, nothing said.
  SweepTable unreferred;
  unreferred.rows = {table.rows[8], table.rows[9]};
  left_out.clear();
  EXPECT_EQ(rowsOfOneReference(unreferred, &left_out).rows.size(), 2u);
  EXPECT_EQ(left_out, "");
  // Two references: the rows of the smaller named, at most four and a count.
  SweepRow other = referredRow(60, 90'000, "x");
  for (int i = 0; i < 6; ++i) {
    other.reference_illuminance_lx = 50'000;
    other.stack_id = fmt::format("o{}", i);
    table.rows.push_back(other);
  }
  const std::string mixed = mixedReferences(table);
  EXPECT_NE(mixed.find("6 row(s) referred to 50 klx: o0 (\u03b1 60\u00b0), o1"), std::string::npos)
      << mixed;
  EXPECT_NE(mixed.find("and 2 more"), std::string::npos) << mixed;
  EXPECT_EQ(mixed.find("r5 "), std::string::npos) << mixed;  // the largest group is the table's
}

}  // namespace
}  // namespace glarecam::pipeline
