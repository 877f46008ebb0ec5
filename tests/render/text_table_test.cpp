#include "render/text_table.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

constexpr Font kTableFont{.size = 10};

const TextTable kTable{
    .rows = {{"name", "value"}, {"first", "1"}, {"second", "22"}, {"third", "333 333"}}};

TEST(TextTable, ColumnsAreAsWideAsTheirWidestCellPlusPadding) {
  TestCanvas canvas(10, 10);
  const std::vector<double> widths = columnWidthsPt(canvas.context(), kTable, kTableFont);
  ASSERT_EQ(widths.size(), 2u);
  const double padding = widths[0] - textWidth(canvas.context(), "second", kTableFont);
  EXPECT_GT(padding, 0);
  EXPECT_DOUBLE_EQ(widths[1], textWidth(canvas.context(), "333 333", kTableFont) + padding);
  // Headings count in bold.
  const TextTable bold_header{.rows = {{"WWWW"}, {"WWWW"}}};
  EXPECT_DOUBLE_EQ(columnWidthsPt(canvas.context(), bold_header, kTableFont)[0],
                   textWidth(canvas.context(), "WWWW", {.size = 10, .bold = true}) + padding);
}

TEST(TextTable, RaggedRowsGetTheWidestRowsColumns) {
  TestCanvas canvas(10, 10);
  const TextTable ragged{.rows = {{"a"}, {"b", "c", "d"}, {"e", "f"}}};
  const std::vector<double> widths = columnWidthsPt(canvas.context(), ragged, kTableFont);
  ASSERT_EQ(widths.size(), 3u);
  EXPECT_GT(widths[2], 0);
}

TEST(TextTable, HeightIsRowsTimesARowHeightScaledByTheFont) {
  EXPECT_DOUBLE_EQ(tableHeightPt(kTable, kTableFont), 4 * 12.0);  // rows 1.2 em apart
  EXPECT_DOUBLE_EQ(tableHeightPt(kTable, {.size = 5}), 4 * 6.0);
  EXPECT_DOUBLE_EQ(tableHeightPt({}, kTableFont), 0);
}

TEST(TextTable, DrawnAtNaturalSizeWhenItFitsShrunkWhenNot) {
  TestCanvas canvas(400, 200);
  EXPECT_DOUBLE_EQ(drawTable(canvas.context(), kTable, {0, 0, 400, 200}, kTableFont), 48);
  double natural_width = 0;
  for (const double w : columnWidthsPt(canvas.context(), kTable, kTableFont)) natural_width += w;
  EXPECT_NEAR(drawTable(canvas.context(), kTable, {0, 0, natural_width / 2, 200}, kTableFont), 24,
              1e-9);
  EXPECT_NEAR(drawTable(canvas.context(), kTable, {0, 0, 400, 36}, kTableFont), 36, 1e-9);
  EXPECT_NEAR(drawTable(canvas.context(), kTable, {0, 0, 1, 1}, kTableFont), 0.3 * 48, 1e-9);
}

TEST(TextTable, EveryOtherDataRowIsStripedAndRulesFrameTheData) {
  TestCanvas canvas(400, 200);
  drawTable(canvas.context(), kTable, {0, 0, 400, 200}, kTableFont);
  // Rows are 12 px: heading [0, 12], first [12, 24], second [24, 36], third [36, 48]. Column 0
  // is right-aligned, so its left padding is blank.
  EXPECT_EQ(canvas.at(1, 18), kWhitePixel);
  const CanvasPixel stripe = canvas.at(1, 30);
  EXPECT_LT(stripe[0], 250);
  EXPECT_GT(stripe[0], 230);
  EXPECT_EQ(canvas.at(1, 42), kWhitePixel);
  EXPECT_LT(canvas.at(1, 11)[0], 230);  // the rule under the heading, centred on y = 12
  EXPECT_LT(canvas.at(1, 47)[0], 230);  // and under the table
  EXPECT_EQ(canvas.at(1, 60), kWhitePixel);
}

TEST(TextTable, FirstColumnLeftAlignedOnRequest) {
  TextTable table{.rows = {{"a much wider heading", "y"}, {"a", "1"}}};
  TestCanvas right(300, 40);
  drawTable(right.context(), table, {0, 0, 300, 40}, kTableFont);
  table.first_column_left = true;
  TestCanvas left(300, 40);
  drawTable(left.context(), table, {0, 0, 300, 40}, kTableFont);
  // The short cell "a" of the data row sits at its column's start, or by default at its end.
  EXPECT_TRUE(left.anyInk(0, 13, 20, 24));
  EXPECT_FALSE(right.anyInk(0, 13, 20, 24));
}

TEST(TextTable, AnyColumnLeftAlignedOnRequest) {
  TextTable table{.rows = {{"x", "a much wider heading"}, {"1", "a"}}};
  TestCanvas right(300, 40);
  const double first_pt = columnWidthsPt(right.context(), table, kTableFont)[0];
  drawTable(right.context(), table, {0, 0, 300, 40}, kTableFont);
  table.left_columns = {1};
  TestCanvas left(300, 40);
  drawTable(left.context(), table, {0, 0, 300, 40}, kTableFont);
  // The second column's short cell "a" at the column's start, or by default at its end.
  const int start = static_cast<int>(first_pt);
  EXPECT_TRUE(left.anyInk(start, 13, start + 20, 24));
  EXPECT_FALSE(right.anyInk(start, 13, start + 20, 24));
}

}  // namespace
}  // namespace glarecam::render
