#include "pipeline/render/markers.h"

#include <cairo.h>

#include <numbers>

namespace glarecam::pipeline {

void drawMarker(cairo_t* cr, Point centre, const MarkerStyle& style) {
  constexpr double kOutlinePt = 0.6;  // the white ring; a hollow marker's outline is twice that
  const double half = style.size_pt / 2;
  if (style.shape == MarkerShape::kCircle) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, centre.x, centre.y, half, 0, 2 * std::numbers::pi);
  } else {
    cairo_rectangle(cr, centre.x - half, centre.y - half, style.size_pt, style.size_pt);
  }
  cairo_set_dash(cr, nullptr, 0, 0);
  if (style.hollow) {
    setColour(cr, kWhite);
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 2 * kOutlinePt);
    setColour(cr, style.colour);
    cairo_stroke(cr);
    return;
  }
  setColour(cr, style.colour);
  cairo_fill_preserve(cr);
  cairo_set_line_width(cr, kOutlinePt);
  setColour(cr, kWhite);
  cairo_stroke(cr);
}

}  // namespace glarecam::pipeline
