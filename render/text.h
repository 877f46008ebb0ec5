// Text on the pictures and the data sheet: one font family (DejaVu Sans, which the Debian
// package fonts-dejavu-core installs), regular or bold, drawn on a baseline, measured, and
// wrapped into lines. Sizes and lengths are in the canvas's user units: points on the data
// sheet, pixels on the pictures. Text is UTF-8.
#pragma once

#include <string>
#include <vector>

#include "render/colour.h"
#include "render/page_geometry.h"
#include "render/page_output.h"

namespace glarecam::render {

inline constexpr const char* kFontFamily = "DejaVu Sans";

struct Font {
  double size = 0;  // the em
  bool bold = false;
};

inline constexpr double kLineSpacingEm = 1.3;  // baseline to baseline
// A baseline this far below a point centres digits and lower-case letters on it.
inline constexpr double kBaselineBelowMiddleEm = 0.35;

// Where drawText's baseline point lies on the text: at its start, middle or end.
enum class Align { kLeft, kCentre, kRight };

struct TextStyle {
  Font font;
  Rgb colour = kInk;
  Align align = Align::kLeft;
  double opacity = 1;  // 0 to 1: what lies under the text shows through
};

// Makes `font` the canvas's font for the text drawn or measured next.
void selectFont(Canvas& canvas, const Font& font);

// The advance of `text` in `font`: where text drawn right after it would start.
double textWidth(Canvas& canvas, const std::string& text, const Font& font);

double lineHeight(const Font& font);

void drawText(Canvas& canvas, Point baseline, const std::string& text, const TextStyle& style);

// Text centred on `centre` (its baseline through it), reading bottom to top.
void drawVerticalText(Canvas& canvas, Point centre, const std::string& text,
                      const TextStyle& style);

// Greedy word wrap at white space to lines no wider than `width` (but a word longer than that
// stands alone on its line).
std::vector<std::string> wrapText(Canvas& canvas, const std::string& text, double width,
                                  const Font& font);

// Each paragraph wrapped to `width`, the first baseline at first_baseline, one line height
// apart; returns the height used.
double drawParagraphs(Canvas& canvas, Point first_baseline, double width,
                      const std::vector<std::string>& paragraphs, const TextStyle& style);

// A word across a page's face, bottom left to top right, with a note in small type under it, in
// pale red: the mark of a page that must never pass for what it is not ("SIMULATED": stacks of
// the simulated camera), whatever is cut from it. `over` false: opaque pale red, to be drawn
// first, under everything; true: translucent red that gives the same pale red on white, drawn
// last, over everything, so that a page covered by opaque rasters shows it and them.
void drawPageMark(Canvas& canvas, const PageSize& page, const std::string& word,
                  const std::string& note, bool over);

}  // namespace glarecam::render
