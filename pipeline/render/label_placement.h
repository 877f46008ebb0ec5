// Where a label goes on a picture: inside the picture, and off the lines drawn there (ellipses,
// contours, axes), so that no number is written over the shape it describes. Pure geometry in
// pixel coordinates; the text's width comes from the caller.
#pragma once

#include <vector>

#include "calibration/camera_model.h"

namespace glarecam::pipeline {

using Polyline = std::vector<calibration::PixelPoint>;

struct PictureBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LabelSpec {
  calibration::PixelPoint at;    // the preferred baseline start
  calibration::PixelPoint away;  // unit direction to move in, away from the shape
  double width_px = 0;
  double font_px = 0;
};

// True when a point of `lines` lies under the text (its box with a quarter em around it). The
// curves drawn have points a few pixels apart, so a line crossing the text has one under it.
bool labelCovers(const calibration::PixelPoint& baseline, double width_px, double font_px,
                 const std::vector<Polyline>& lines);

// The label's baseline start: `at` kept inside `box`; when that covers a line, moved along `away`
// in steps of a quarter em, up to 8 em, to the first place (inside `box`) that covers none;
// `at` inside `box` when there is none.
calibration::PixelPoint placeLabel(const LabelSpec& label, const PictureBox& box,
                                   const std::vector<Polyline>& lines);

}  // namespace glarecam::pipeline
