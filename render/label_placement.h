// Where a label goes on a picture: inside the picture, and off the lines drawn there (ellipses,
// contours, axes), so that no number is written over the shape it describes. Pure geometry in
// the picture's user units (pixels; page_geometry.h); the text's width comes from the caller.
#pragma once

#include <vector>

#include "render/page_geometry.h"

namespace glarecam::render {

using Polyline = std::vector<Point>;

struct LabelSpec {
  Point at;    // the preferred baseline start
  Point away;  // unit direction to move in, away from the shape
  double width_px = 0;
  double font_px = 0;
};

// True when a point of `lines` lies under the text (its box with a quarter em around it). The
// curves drawn have points a few pixels apart, so a line crossing the text has one under it.
bool labelCovers(const Point& baseline, double width_px, double font_px,
                 const std::vector<Polyline>& lines);

// The label's baseline start: `at` kept inside `box`; when that covers a line, moved along `away`
// in steps of a quarter em, up to 8 em, to the first place (inside `box`) that covers none;
// `at` inside `box` when there is none.
Point placeLabel(const LabelSpec& label, const Box& box, const std::vector<Polyline>& lines);

}  // namespace glarecam::render
