// Markers of measured points in the plots: a filled circle or square with a thin white ring, so
// that a marker stays distinct from a line under it, or a hollow one (white inside) for a value
// that is only a bound. Lengths are in points (pt, 1/72 in), the data sheet's user units.
#pragma once

#include "render/colour.h"
#include "render/page_geometry.h"

namespace glarecam::render {

enum class MarkerShape { kCircle, kSquare };

struct MarkerStyle {
  Rgb colour;
  MarkerShape shape = MarkerShape::kCircle;
  double size_pt = 4.6;  // diameter or side
  bool hollow = false;
};

void drawMarker(Canvas& canvas, Point centre, const MarkerStyle& style);

}  // namespace glarecam::render
