// False colour: the values of a float image on a logarithmic scale, through the Turbo colour map
// (Google, 2019), painted on a raster (rgb_surface.h) pixel by pixel, each pixel enlarged to a
// square block by a whole factor when asked. Pixels that stand for something else than a value
// on the scale show in colours of their own: a mark image (one byte a pixel, the values' size)
// names them, and each mark may have its colour (saturated pixels white, say); a value that is
// not finite is black. Knows nothing of what the values are.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "core/image.h"
#include "render/colour.h"
#include "render/rgb_surface.h"

namespace glarecam::render {

// Turbo colour map (polynomial approximation), t in [0, 1] (clamped).
void turboColour(double t, std::uint8_t rgb[3]);

// A logarithmic scale from 10^log_min to 10^log_max.
struct LogScale {
  double log_min = 0, log_max = 1;
  double position(double value) const;  // 0 at the bottom, 1 at the top, clamped
};

// The colour of a mark's pixels, by mark; none: the pixel's value is shown.
using MarkColours = std::array<std::optional<Rgb>, 256>;

// `values` on `surface` from its top left corner, pixel (x, y) as the block of zoom × zoom
// pixels at (zoom x, zoom y), which the surface must hold.
void paintFalseColour(RgbSurface& surface, const FloatImage& values, const ByteImage& marks,
                      const MarkColours& mark_colours, const LogScale& scale, int zoom);

}  // namespace glarecam::render
