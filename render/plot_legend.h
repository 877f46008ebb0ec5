// A plot's legend: one row an entry, a sample of its line and/or marker then its label, on a
// nearly opaque white box in the corner of the data area that hides the least ink (plot_axes.h;
// ties go to the top left, then clockwise). Lengths are in points (pt, 1/72 in).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/line_style.h"
#include "render/markers.h"
#include "render/plot_axes.h"

namespace glarecam::render {

struct LegendEntry {
  std::string label;
  std::optional<LineStyle> line;
  std::optional<MarkerStyle> marker;  // drawn over the middle of the line sample
};

void drawLegend(Canvas& canvas, const Plot& plot, const std::vector<LegendEntry>& entries);

}  // namespace glarecam::render
