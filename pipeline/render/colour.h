// Colours as red, green and blue, each from 0 to 1 (Cairo's source colours, sRGB), the neutral
// inks the toolkit draws with by default, setting a colour as a context's source, and painting
// a background.
#pragma once

#include "pipeline/render/cairo_handles.h"

namespace glarecam::pipeline {

struct Rgb {
  double r = 0, g = 0, b = 0;
};

inline constexpr Rgb kWhite{1, 1, 1};
inline constexpr Rgb kInk{0.10, 0.10, 0.12};          // text, near-black
inline constexpr Rgb kFrameColour{0.45, 0.45, 0.48};  // plot frames, ticks, table rules

// `colour` moved toward white by `fraction` (0: unchanged, 1: white) of the way.
Rgb lightened(const Rgb& colour, double fraction);

// alpha: opacity, 0 (transparent) to 1.
void setColour(cairo_t* cr, const Rgb& colour, double alpha = 1);

// Fills everything inside the current clip (the whole surface by default).
void paint(cairo_t* cr, const Rgb& colour);

}  // namespace glarecam::pipeline
