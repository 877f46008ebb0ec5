// The raster the pictures are drawn on: a Cairo image surface of 24-bit RGB (Cairo's RGB24, one
// native-endian 32-bit word a pixel, 0x00RRGGBB), drawn on through a Canvas (canvas.h) or
// written pixel by pixel, and its pixels copied out as 8-bit RGB for writing (core/image_io.h).
// Sizes in pixels; the first row is the top one. A surface moves, never copies.
#pragma once

#include <cstdint>
#include <vector>

#include "core/error.h"
#include "render/cairo_handles.h"

namespace glarecam::render {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel
};

class RgbSurface {
 public:
  // A black surface; an error when Cairo cannot make one that size (too large, out of memory).
  static Result<RgbSurface> create(int width_px, int height_px);

  int width() const;
  int height() const;

  // The pixels, after what has been drawn on the surface.
  RgbImage copyRgb() const;

  // The pixels to write directly, row by row (from several threads if need be): what was drawn
  // before is flushed first, and Cairo learns of what was written when the access goes. Nothing
  // may be drawn on the surface meanwhile.
  class [[nodiscard]] Pixels {
   public:
    ~Pixels();
    Pixels(const Pixels&) = delete;
    Pixels& operator=(const Pixels&) = delete;

    // The row's width() words, 0x00RRGGBB (the top byte is ignored).
    std::uint32_t* row(int y) const;

   private:
    friend class RgbSurface;
    explicit Pixels(cairo_surface_t* surface);
    cairo_surface_t* surface_;
    unsigned char* data_;
    int stride_;
  };
  Pixels pixels();

 private:
  friend class Canvas;  // draws on it
  explicit RgbSurface(CairoSurface surface) : surface_(std::move(surface)) {}
  CairoSurface surface_;
};

}  // namespace glarecam::render
