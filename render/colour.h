// Colours as red, green and blue, each from 0 to 1 (Cairo's source colours, sRGB), the neutral
// inks the toolkit draws with by default, a colour as the bytes of a raster, and painting a
// background.
#pragma once

#include <array>
#include <cstdint>

namespace glarecam::render {

class Canvas;

struct Rgb {
  double r = 0, g = 0, b = 0;
};

inline constexpr Rgb kWhite{1, 1, 1};
inline constexpr Rgb kInk{0.10, 0.10, 0.12};          // text, near-black
inline constexpr Rgb kFrameColour{0.45, 0.45, 0.48};  // plot frames, ticks, table rules

// `colour` moved toward white by `fraction` (0: unchanged, 1: white) of the way.
Rgb lightened(const Rgb& colour, double fraction);

// The colour as 8-bit red, green and blue, each rounded (and clamped to 0…255).
std::array<std::uint8_t, 3> rgbBytes(const Rgb& colour);

// Fills everything inside the current clip (the whole surface by default).
void paint(Canvas& canvas, const Rgb& colour);

}  // namespace glarecam::render
