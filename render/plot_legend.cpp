#include "render/plot_legend.h"

#include <algorithm>
#include <array>

#include "render/canvas.h"
#include "render/text.h"

namespace glarecam::render {
namespace {

constexpr double kLegendSamplePt = 20;  // length of a line sample
constexpr double kLegendPaddingPt = 4;
constexpr double kLegendInsetPt = 5;  // from the data area's frame
constexpr double kLegendRowGapPt = 1;
constexpr double kBackgroundAlpha = 0.88;
constexpr Font kLegendFont{.size = 7};

// An entry with its sample starting at `left`, the sample centred on `middle_y`.
void drawLegendEntry(Canvas& canvas, double left, double middle_y, const LegendEntry& entry) {
  if (entry.line)
    drawSegment(canvas, {left, middle_y}, {left + kLegendSamplePt, middle_y}, *entry.line);
  if (entry.marker) drawMarker(canvas, {left + kLegendSamplePt / 2, middle_y}, *entry.marker);
  drawText(canvas,
           {left + kLegendSamplePt + kLegendPaddingPt,
            middle_y + kBaselineBelowMiddleEm * kLegendFont.size},
           entry.label, {kLegendFont});
}

double inkInside(const Plot& plot, const Box& box) {
  double total = 0;
  for (const Ink& ink : plot.ink)
    if (box.contains(ink.at)) total += ink.weight;
  return total;
}

Box legendBox(const Plot& plot, double width, double height) {
  const Box& a = plot.area;
  const double left = a.x0 + kLegendInsetPt, right = a.x1 - kLegendInsetPt - width;
  const double top = a.y0 + kLegendInsetPt, bottom = a.y1 - kLegendInsetPt - height;
  const std::array<Box, 4> corners = {Box{left, top, left + width, top + height},
                                      Box{right, top, right + width, top + height},
                                      Box{right, bottom, right + width, bottom + height},
                                      Box{left, bottom, left + width, bottom + height}};
  return *std::min_element(corners.begin(), corners.end(), [&](const Box& p, const Box& q) {
    return inkInside(plot, p) < inkInside(plot, q);
  });
}

}  // namespace

void drawLegend(Canvas& canvas, const Plot& plot, const std::vector<LegendEntry>& entries) {
  const double row_pt = lineHeight(kLegendFont) + kLegendRowGapPt;
  double text_width = 0;
  for (const LegendEntry& e : entries)
    text_width = std::max(text_width, textWidth(canvas, e.label, kLegendFont));
  const Box box = legendBox(plot, 3 * kLegendPaddingPt + kLegendSamplePt + text_width,
                            2 * kLegendPaddingPt + row_pt * entries.size());
  canvas.rectangle(box);
  canvas.setColour(kWhite, kBackgroundAlpha);
  canvas.fillPreserve();
  applyLineStyle(canvas, kGridStyle);
  canvas.stroke();
  double middle_y = box.y0 + kLegendPaddingPt + row_pt / 2;
  for (const LegendEntry& entry : entries) {
    drawLegendEntry(canvas, box.x0 + kLegendPaddingPt, middle_y, entry);
    middle_y += row_pt;
  }
}

}  // namespace glarecam::render
