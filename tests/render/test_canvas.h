// A small white raster to draw on with the render toolkit and read back, for the toolkit's
// tests. One user unit is one pixel; pixel (x, y) covers [x, x + 1] × [y, y + 1].
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>

#include "render/canvas.h"
#include "render/colour.h"
#include "render/rgb_surface.h"

namespace glarecam::render {

using CanvasPixel = std::array<std::uint8_t, 3>;

// A missing value in a series: drawn as a gap, skipped by the axes.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The red, green and blue bytes of pixel (x, y).
inline const std::uint8_t* rgbPixel(const RgbImage& image, int x, int y) {
  return image.rgb.data() + (static_cast<std::size_t>(y) * image.width + x) * 3;
}

struct TestCanvas {
  RgbSurface surface;
  Canvas canvas;

  TestCanvas(int width_px, int height_px, const Rgb& background = kWhite)
      : surface(RgbSurface::create(width_px, height_px).value()),
        canvas(Canvas::onSurface(surface).value()) {
    paint(canvas, background);
  }

  Canvas& context() { return canvas; }

  RgbImage image() const { return surface.copyRgb(); }

  CanvasPixel at(int x, int y) const {
    const RgbImage pixels = image();
    const std::uint8_t* p = rgbPixel(pixels, x, y);
    return {p[0], p[1], p[2]};
  }

  // Whether any pixel in [x0, x1) × [y0, y1) is darker than `below` in some channel.
  bool anyInk(int x0, int y0, int x1, int y1, int below = 200) const {
    const RgbImage pixels = image();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c)
          if (rgbPixel(pixels, x, y)[c] < below) return true;
    return false;
  }
};

inline constexpr CanvasPixel kWhitePixel{255, 255, 255};
inline constexpr CanvasPixel kBlackPixel{0, 0, 0};
inline constexpr CanvasPixel kRedPixel{255, 0, 0};

}  // namespace glarecam::render
