#include "pipeline/render/colour.h"

#include <cairo.h>

namespace glarecam::pipeline {

Rgb lightened(const Rgb& colour, double fraction) {
  const auto lighten = [fraction](double c) { return c + (1 - c) * fraction; };
  return {lighten(colour.r), lighten(colour.g), lighten(colour.b)};
}

void setColour(cairo_t* cr, const Rgb& colour, double alpha) {
  cairo_set_source_rgba(cr, colour.r, colour.g, colour.b, alpha);
}

void paint(cairo_t* cr, const Rgb& colour) {
  setColour(cr, colour);
  cairo_paint(cr);
}

}  // namespace glarecam::pipeline
