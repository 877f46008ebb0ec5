#include "render/text_table.h"

#include <algorithm>

#include "render/canvas.h"

namespace glarecam::render {
namespace {

constexpr double kRowHeightEm = 1.2;    // closer than text lines: the stripes keep rows apart
constexpr double kCellPaddingEm = 0.6;  // each side of a cell's text
constexpr double kMinScale = 0.3;       // a box far too small gets a tiny table, not a negative one
constexpr Rgb kStripeColour{0.95, 0.95, 0.96};

Font cellFont(const TextTable& table, std::size_t row, Font font) {
  font.bold = row < table.header_rows;
  return font;
}

double rowHeightPt(const Font& font) { return font.size * kRowHeightEm; }

void drawTableRow(Canvas& canvas, const TextTable& table, std::size_t r,
                  const std::vector<double>& widths, Point top_left, const Font& font) {
  const double baseline = top_left.y + rowHeightPt(font) / 2 + kBaselineBelowMiddleEm * font.size;
  const double padding = kCellPaddingEm * font.size;
  double x = top_left.x;
  const std::vector<std::string>& row = table.rows[r];
  for (std::size_t c = 0; c < row.size(); ++c) {
    const bool left = (c == 0 && table.first_column_left) ||
                      std::find(table.left_columns.begin(), table.left_columns.end(), c) !=
                          table.left_columns.end();
    const Point at{left ? x + padding : x + widths[c] - padding, baseline};
    drawText(canvas, at, row[c],
             {cellFont(table, r, font), kInk, left ? Align::kLeft : Align::kRight});
    x += widths[c];
  }
}

}  // namespace

std::vector<double> columnWidthsPt(Canvas& canvas, const TextTable& table, const Font& font) {
  std::vector<double> widths;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    widths.resize(std::max(widths.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c)
      widths[c] = std::max(widths[c], textWidth(canvas, row[c], cellFont(table, r, font)) +
                                          2 * kCellPaddingEm * font.size);
  }
  return widths;
}

double tableHeightPt(const TextTable& table, const Font& font) {
  return table.rows.size() * rowHeightPt(font);
}

double drawTable(Canvas& canvas, const TextTable& table, const Box& box, const Font& font) {
  std::vector<double> widths = columnWidthsPt(canvas, table, font);
  double natural_width = 0;
  for (const double w : widths) natural_width += w;
  const double scale = std::max(kMinScale, std::min({1.0, box.width() / natural_width,
                                                     box.height() / tableHeightPt(table, font)}));
  const Font fitted{font.size * scale, font.bold};
  for (double& w : widths) w *= scale;
  const double row_pt = rowHeightPt(fitted), width = natural_width * scale;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double top = box.y0 + r * row_pt;
    if (r >= table.header_rows && (r - table.header_rows) % 2 == 1) {
      canvas.setColour(kStripeColour);
      canvas.rectangle({box.x0, top}, width, row_pt);
      canvas.fill();
    }
    drawTableRow(canvas, table, r, widths, {box.x0, top}, fitted);
  }
  const double rule_y = box.y0 + table.header_rows * row_pt;
  drawSegment(canvas, {box.x0, rule_y}, {box.x0 + width, rule_y}, kRuleStyle);
  const double bottom = box.y0 + tableHeightPt(table, fitted);
  drawSegment(canvas, {box.x0, bottom}, {box.x0 + width, bottom}, kRuleStyle);
  return tableHeightPt(table, fitted);
}

}  // namespace glarecam::render
