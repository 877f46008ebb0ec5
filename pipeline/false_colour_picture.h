// False-colour picture of a luminance image for people: log-scaled luminance in the Turbo
// colour map (false_colour.h), with a labelled colour bar in cd/m² to the right, the glare limit
// marked on the bar, saturated pixels (lower bounds) in white and under-exposed ones in black, and
// an optional overlay (the glare ellipses of glare_picture.h) drawn over the image. Pure function:
// returns an 8-bit RGB raster; writing it is the caller's business.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calibration/hdr_merge.h"
#include "core/error.h"
#include "render/colour.h"
#include "render/rgb_surface.h"

namespace glarecam::pipeline {

// A drawing over the image part of the picture (glare_picture.h), clipped to it, in pixel-centre
// coordinates (core/image.h: the centre of pixel (x, y) is at (x, y)): gets the canvas and the
// label font size in pixels.
using PictureOverlay = std::function<void(render::Canvas& canvas, double font_px)>;

// The glare limit's colour: its mark on the colour bar, the limit contour over the image.
inline constexpr render::Rgb kLimitColour{1, 0, 1};  // magenta: no colour of the Turbo map

struct FalseColourOptions {
  std::optional<double>
      min_cd_m2;  // bottom of the scale; default: 1st percentile, at most 6 decades below max
  std::optional<double> max_cd_m2;    // top of the scale; default: the image maximum
  std::optional<double> limit_cd_m2;  // marked on the colour bar when given
  std::string title;                  // drawn above the colour bar (e.g. "α 40°")
  // Lines under the title (the stack, Lmax, the limit, the verdict), each shrunk to the panel's
  // width when longer.
  std::vector<std::string> caption;
  // Across the top of the image on a band of kLimitColour, when not empty: a warning no one who
  // looks at the picture can miss (e.g. "SUSPECT: frames disagree with the merge").
  std::string banner;
  // A frame shorter than this is drawn enlarged by a whole factor (each pixel a square block, at
  // most kMaxPictureZoom), so that a small frame's spot, ellipses and labels stay readable; 0:
  // pixel for pixel. The overlay still draws in the frame's pixel coordinates.
  int min_image_height_px = 0;
  PictureOverlay overlay;  // optional
};

inline constexpr int kMaxPictureZoom = 8;

Result<render::RgbImage> renderFalseColour(const calibration::MergedImage& merged,
                                           const FalseColourOptions& options = {});

}  // namespace glarecam::pipeline
