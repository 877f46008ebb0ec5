#include "pipeline/render/text.h"

#include <cairo.h>

#include <numbers>
#include <sstream>

namespace glarecam::pipeline {

void selectFont(cairo_t* cr, const Font& font) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font.size);
}

double textWidth(cairo_t* cr, const std::string& text, const Font& font) {
  selectFont(cr, font);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

double lineHeight(const Font& font) { return font.size * kLineSpacingEm; }

void drawText(cairo_t* cr, Point baseline, const std::string& text, const TextStyle& style) {
  const double width = textWidth(cr, text, style.font);
  const double shift = style.align == Align::kLeft     ? 0
                       : style.align == Align::kCentre ? width / 2
                                                       : width;
  setColour(cr, style.colour);
  cairo_move_to(cr, baseline.x - shift, baseline.y);
  cairo_show_text(cr, text.c_str());
}

void drawVerticalText(cairo_t* cr, Point centre, const std::string& text, const TextStyle& style) {
  cairo_save(cr);
  cairo_translate(cr, centre.x, centre.y);
  cairo_rotate(cr, -std::numbers::pi / 2);
  drawText(cr, {0, 0}, text, {style.font, style.colour, Align::kCentre});
  cairo_restore(cr);
}

std::vector<std::string> wrapText(cairo_t* cr, const std::string& text, double width,
                                  const Font& font) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && textWidth(cr, candidate, font) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

double drawParagraphs(cairo_t* cr, Point first_baseline, double width,
                      const std::vector<std::string>& paragraphs, const TextStyle& style) {
  double y = first_baseline.y;
  for (const std::string& paragraph : paragraphs) {
    for (const std::string& line : wrapText(cr, paragraph, width, style.font)) {
      drawText(cr, {first_baseline.x, y}, line, style);
      y += lineHeight(style.font);
    }
  }
  return y - first_baseline.y;
}

}  // namespace glarecam::pipeline
