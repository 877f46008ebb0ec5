#include "render/line_style.h"

#include <array>
#include <span>

#include "render/canvas.h"

namespace glarecam::render {

void applyLineStyle(Canvas& canvas, const LineStyle& style) {
  static constexpr std::array<double, 2> kDashedPt = {4.0, 2.5};
  static constexpr std::array<double, 2> kLongDashedPt = {8.0, 3.0};
  static constexpr std::array<double, 2> kDottedPt = {0.0, 2.4};  // round caps make the dots
  canvas.setColour(style.colour);
  canvas.setLineWidth(style.width_pt);
  canvas.setLineJoin(LineJoin::kRound);
  canvas.setLineCap(style.dash == Dash::kDotted ? LineCap::kRound : LineCap::kButt);
  const std::array<double, 2>* pattern = style.dash == Dash::kDashed       ? &kDashedPt
                                         : style.dash == Dash::kLongDashed ? &kLongDashedPt
                                         : style.dash == Dash::kDotted     ? &kDottedPt
                                                                           : nullptr;
  canvas.setDash(pattern ? std::span<const double>(*pattern) : std::span<const double>());
}

void drawSegment(Canvas& canvas, Point from, Point to, const LineStyle& style) {
  applyLineStyle(canvas, style);
  canvas.moveTo(from);
  canvas.lineTo(to);
  canvas.stroke();
}

}  // namespace glarecam::render
