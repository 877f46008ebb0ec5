#include "render/markers.h"

#include <numbers>

#include "render/canvas.h"

namespace glarecam::render {

void drawMarker(Canvas& canvas, Point centre, const MarkerStyle& style) {
  constexpr double kOutlinePt = 0.6;  // the white ring; a hollow marker's outline is twice that
  const double half = style.size_pt / 2;
  if (style.shape == MarkerShape::kCircle) {
    canvas.newSubPath();
    canvas.arc(centre, half, 0, 2 * std::numbers::pi);
  } else {
    canvas.rectangle({centre.x - half, centre.y - half}, style.size_pt, style.size_pt);
  }
  canvas.setDash({});
  if (style.hollow) {
    canvas.setColour(kWhite);
    canvas.fillPreserve();
    canvas.setLineWidth(2 * kOutlinePt);
    canvas.setColour(style.colour);
    canvas.stroke();
    return;
  }
  canvas.setColour(style.colour);
  canvas.fillPreserve();
  canvas.setLineWidth(kOutlinePt);
  canvas.setColour(kWhite);
  canvas.stroke();
}

}  // namespace glarecam::render
