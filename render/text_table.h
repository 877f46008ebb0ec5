// Tables of text: rows of cells, the first rows headings (bold), data rows striped every other
// row, a rule under the headings and one under the table. Columns are as wide as their widest
// cell plus padding; every column is right-aligned (numbers), but the first may be left-aligned
// (names), and so may any other listed in left_columns (words). Lengths are in points (pt, 1/72
// in), the data sheet's user units; padding and row height scale with the font.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "render/line_style.h"
#include "render/page_geometry.h"
#include "render/text.h"

namespace glarecam::render {

struct TextTable {
  std::vector<std::vector<std::string>> rows;  // the first header_rows are headings
  std::size_t header_rows = 1;
  bool first_column_left = false;
  std::vector<std::size_t> left_columns{};  // more left-aligned columns, by index from 0
};

inline constexpr LineStyle kRuleStyle{.colour = kFrameColour, .width_pt = 0.6};

// Each column's width in `font` (the headings in its bold), padding included.
std::vector<double> columnWidthsPt(Canvas& canvas, const TextTable& table, const Font& font);

double tableHeightPt(const TextTable& table, const Font& font);

// The table at the top left of `box`, its font shrunk (never grown, and not below 30 %) so that
// it fits the box. Returns the height drawn.
double drawTable(Canvas& canvas, const TextTable& table, const Box& box, const Font& font);

}  // namespace glarecam::render
