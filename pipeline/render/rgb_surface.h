// The raster the pictures are drawn on: a Cairo image surface of 24-bit RGB (Cairo's RGB24, one
// native-endian 32-bit word a pixel, 0x00RRGGBB), and its pixels copied out as 8-bit RGB for
// writing (core/image_io.h). Sizes in pixels; the first row is the top one.
#pragma once

#include <cstdint>
#include <vector>

#include "core/error.h"
#include "pipeline/render/cairo_handles.h"

namespace glarecam::pipeline {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel
};

// A black surface; an error when Cairo cannot make one that size (too large, out of memory).
Result<CairoSurface> createRgbSurface(int width_px, int height_px);

// The pixels of an RGB24 image surface, after what has been drawn on it.
RgbImage copyRgb(cairo_surface_t* surface);

}  // namespace glarecam::pipeline
