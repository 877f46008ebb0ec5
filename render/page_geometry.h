// Points and boxes in a drawing's user space (Cairo's term): x to the right, y down, in the
// canvas's units (PostScript points on the data sheet, whose raster preview scales the
// canvas; pixels on the pictures).
#pragma once

namespace glarecam::render {

struct Point {
  double x = 0, y = 0;
};

// The rectangle from (x0, y0), its top left corner, to (x1, y1).
struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool contains(Point p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};

}  // namespace glarecam::render
