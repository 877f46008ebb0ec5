// contours.csv: a result's ladder as rows, written sorted by α and level and read back equal
// (numbers in their shortest exact form), and what is not a contour table refused naming the
// file, the line and the column.
#include "pipeline/contour_table.h"

#include <gtest/gtest.h>

#include "support/test_support.h"
#include "tests/pipeline/result_fixture.h"

namespace glarecam::pipeline {
namespace {

namespace fs = std::filesystem;

ResultEllipse someEllipse(double vertical_deg, double horizontal_deg) {
  ResultEllipse e;
  e.vertical_deg = vertical_deg;
  e.horizontal_deg = horizontal_deg;
  e.major_deg = std::max(vertical_deg, horizontal_deg);
  e.minor_deg = std::min(vertical_deg, horizontal_deg);
  e.orientation_deg = 88.5;
  e.solid_angle_sr = 0.0123;
  e.vertical_uncertainty_deg = 0.05;
  e.horizontal_uncertainty_deg = 0.04;
  e.orientation_uncertainty_deg = std::nullopt;  // a circle has none
  e.solid_angle_uncertainty_sr = 1.5e-4;
  return e;
}

StackResult resultWithLadder(double alpha_deg, const std::string& stack) {
  StackResult result = testing::minimalResult(2.5e5, alpha_deg);
  result.stack = stack;
  result.illuminance.reference_lx = 100'000;
  result.contours = std::vector<ResultContour>{
      {ContourKind::kLadder,
       {.level_cd_m2 = 1e4, .status = EllipseStatus::kMeasured, .ellipse = someEllipse(9.5, 8.25)}},
      {ContourKind::kLimit,
       {.level_cd_m2 = 3e4, .status = EllipseStatus::kMeasured, .ellipse = someEllipse(7, 6.5)}},
      {ContourKind::kHalfMaximum, {.level_cd_m2 = 1.25e5, .status = EllipseStatus::kTooSmall}}};
  return result;
}

TEST(ContourTable, AResultsLadderWritesAndReadsBack) {
  const std::vector<ContourRow> rows = contourRowsFromResult(resultWithLadder(40, "s-40"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].stack_id, "s-40");
  EXPECT_EQ(rows[0].alpha_deg, 40);
  EXPECT_EQ(rows[0].vertical_deg, 9.5);
  EXPECT_EQ(rows[0].orientation_uncertainty_deg, std::nullopt);
  EXPECT_EQ(rows[0].reference_illuminance_lx, 100'000);
  EXPECT_EQ(rows[2].kind, ContourKind::kHalfMaximum);
  EXPECT_FALSE(rows[2].vertical_deg);
  // No α or no ladder: no rows.
  EXPECT_TRUE(contourRowsFromResult(testing::minimalResult(2.5e5)).empty());
  EXPECT_TRUE(contourRowsFromResult(testing::minimalResult(2.5e5, 40)).empty());

  ContourTable table;
  for (const ContourRow& row : contourRowsFromResult(resultWithLadder(60, "s-60, \"b\"")))
    table.rows.push_back(row);
  for (const ContourRow& row : rows) table.rows.push_back(row);
  const std::string text = formatContourTable(table);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "stack_id,alpha_deg,level_cd_m2,kind,status,vertical_deg,horizontal_deg,"
            "orientation_deg,solid_angle_sr,vertical_uncertainty_deg,horizontal_uncertainty_deg,"
            "orientation_uncertainty_deg,solid_angle_uncertainty_sr,reference_illuminance_lx");
  EXPECT_NE(text.find("\ns-40,40,10000,ladder,measured,9.5,8.25,88.5,0.0123,0.05,0.04,,0.00015,"
                      "100000\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\ns-40,40,125000,half_maximum,too_small,,,,,,,,,100000\n"),
            std::string::npos)
      << text;
  testing::TempDir dir;
  testing::writeText(dir / "contours.csv", text);
  const auto read = readContourTable(dir / "contours.csv");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->rows.size(), 6u);
  // Sorted by α: the α 40 rows first.
  EXPECT_EQ(std::vector<ContourRow>(read->rows.begin(), read->rows.begin() + 3), rows);
  EXPECT_EQ(read->rows[3].stack_id, "s-60, \"b\"");
}

TEST(ContourTable, WhatIsNotAContourTableIsRefusedNamingTheLine) {
  testing::TempDir dir;
  ContourTable table;
  table.rows = contourRowsFromResult(resultWithLadder(40, "s"));
  const std::string good = formatContourTable(table);
  const std::string header = good.substr(0, good.find('\n') + 1);
  const auto refusal = [&](const std::string& text) {
    testing::writeText(dir / "c.csv", text);
    const auto read = readContourTable(dir / "c.csv");
    if (read) return std::string("(read)");
    EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
    return read.error().message;
  };
  const std::string file = (dir / "c.csv").string();
  EXPECT_EQ(refusal(""), file + ": empty contour table (no header)");
  EXPECT_EQ(refusal("stack_id,alpha_deg\n"), file + ":1: the header lacks the column level_cd_m2");
  EXPECT_EQ(refusal(header + "s,40,10000,rung,below_level,,,,,,,,,\n"),
            file + ":2: kind: \"rung\" is not ladder, limit or half_maximum");
  EXPECT_EQ(refusal(header + "s,40,30000,ladder,below_level,,,,,,,,,\n"),
            file + ":2: level_cd_m2: 30000 is not a level of the ladder");
  EXPECT_EQ(refusal(header + "s,40,10000,ladder,lost,,,,,,,,,\n"),
            file + ":2: status: \"lost\" is not an ellipse status");
  EXPECT_EQ(refusal(header + "s,95,10000,ladder,below_level,,,,,,,,,\n"),
            file + ":2: alpha_deg: 95 is outside [0, 90)");
  EXPECT_EQ(refusal(header + "s,40,10000,ladder,measured,5,,0,0.01,0.1,0.1,,0.001,\n"),
            file +
                ":2: status measured, but an ellipse column (axes, orientation, solid angle "
                "and their uncertainties) is empty");
  EXPECT_EQ(refusal(header + "s,40,10000,ladder,below_level,5,,,,,,,,\n"),
            file + ":2: status below_level, but the ellipse's columns are given");
  EXPECT_EQ(refusal(header + "s,40,10000,ladder,measured,200,5,0,0.01,0.1,0.1,,0.001,\n"),
            file + ":2: an axis of 200° is outside (0, 180]");
  EXPECT_EQ(refusal(header + "s,40,1e4x,ladder,below_level,,,,,,,,,\n"),
            file + ":2: level_cd_m2: \"1e4x\" is not a number");
}

}  // namespace
}  // namespace glarecam::pipeline
