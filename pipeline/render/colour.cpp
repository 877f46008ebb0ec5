#include "pipeline/render/colour.h"

#include "pipeline/render/canvas.h"

namespace glarecam::pipeline {

Rgb lightened(const Rgb& colour, double fraction) {
  const auto lighten = [fraction](double c) { return c + (1 - c) * fraction; };
  return {lighten(colour.r), lighten(colour.g), lighten(colour.b)};
}

void paint(Canvas& canvas, const Rgb& colour) {
  canvas.setColour(colour);
  canvas.paint();
}

}  // namespace glarecam::pipeline
