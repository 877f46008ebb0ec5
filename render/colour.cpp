#include "render/colour.h"

#include <algorithm>
#include <cmath>

#include "render/canvas.h"

namespace glarecam::render {

Rgb lightened(const Rgb& colour, double fraction) {
  const auto lighten = [fraction](double c) { return c + (1 - c) * fraction; };
  return {lighten(colour.r), lighten(colour.g), lighten(colour.b)};
}

std::array<std::uint8_t, 3> rgbBytes(const Rgb& colour) {
  const auto byte = [](double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
  };
  return {byte(colour.r), byte(colour.g), byte(colour.b)};
}

void paint(Canvas& canvas, const Rgb& colour) {
  canvas.setColour(colour);
  canvas.paint();
}

}  // namespace glarecam::render
