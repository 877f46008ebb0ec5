// Stroked lines of the plots and tables: colour, width and dash pattern. Lengths are in points
// (pt, 1/72 in), the user units of the data sheet, for which the dash patterns are made.
#pragma once

#include "render/colour.h"
#include "render/page_geometry.h"

namespace glarecam::render {

enum class Dash { kSolid, kDashed, kLongDashed, kDotted };

struct LineStyle {
  Rgb colour;
  double width_pt = 1.2;
  Dash dash = Dash::kSolid;
};

// Sets colour, width, round joins, the dash pattern and its caps (dots are round caps on
// zero-length dashes) for the next stroke.
void applyLineStyle(Canvas& canvas, const LineStyle& style);

void drawSegment(Canvas& canvas, Point from, Point to, const LineStyle& style);

}  // namespace glarecam::render
