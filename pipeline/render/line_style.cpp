#include "pipeline/render/line_style.h"

#include <cairo.h>

#include <array>

namespace glarecam::pipeline {

void applyLineStyle(cairo_t* cr, const LineStyle& style) {
  static constexpr std::array<double, 2> kDashedPt = {4.0, 2.5};
  static constexpr std::array<double, 2> kLongDashedPt = {8.0, 3.0};
  static constexpr std::array<double, 2> kDottedPt = {0.0, 2.4};  // round caps make the dots
  setColour(cr, style.colour);
  cairo_set_line_width(cr, style.width_pt);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, style.dash == Dash::kDotted ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
  const std::array<double, 2>* pattern = style.dash == Dash::kDashed       ? &kDashedPt
                                         : style.dash == Dash::kLongDashed ? &kLongDashedPt
                                         : style.dash == Dash::kDotted     ? &kDottedPt
                                                                           : nullptr;
  cairo_set_dash(cr, pattern ? pattern->data() : nullptr, pattern ? 2 : 0, 0);
}

void drawSegment(cairo_t* cr, Point from, Point to, const LineStyle& style) {
  applyLineStyle(cr, style);
  cairo_move_to(cr, from.x, from.y);
  cairo_line_to(cr, to.x, to.y);
  cairo_stroke(cr);
}

}  // namespace glarecam::pipeline
