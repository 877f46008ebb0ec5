#include "render/text.h"

#include <numbers>
#include <sstream>

#include "render/canvas.h"

namespace glarecam::render {

void selectFont(Canvas& canvas, const Font& font) {
  canvas.selectFont(kFontFamily, font.bold, font.size);
}

double textWidth(Canvas& canvas, const std::string& text, const Font& font) {
  selectFont(canvas, font);
  return canvas.textAdvance(text);
}

double lineHeight(const Font& font) { return font.size * kLineSpacingEm; }

void drawText(Canvas& canvas, Point baseline, const std::string& text, const TextStyle& style) {
  const double width = textWidth(canvas, text, style.font);
  const double shift = style.align == Align::kLeft     ? 0
                       : style.align == Align::kCentre ? width / 2
                                                       : width;
  canvas.setColour(style.colour, style.opacity);
  canvas.moveTo({baseline.x - shift, baseline.y});
  canvas.showText(text);
}

void drawVerticalText(Canvas& canvas, Point centre, const std::string& text,
                      const TextStyle& style) {
  const Canvas::Saved saved = canvas.save();
  canvas.translate(centre.x, centre.y);
  canvas.rotate(-std::numbers::pi / 2);
  drawText(canvas, {0, 0}, text, {style.font, style.colour, Align::kCentre, style.opacity});
}

std::vector<std::string> wrapText(Canvas& canvas, const std::string& text, double width,
                                  const Font& font) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && textWidth(canvas, candidate, font) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

double drawParagraphs(Canvas& canvas, Point first_baseline, double width,
                      const std::vector<std::string>& paragraphs, const TextStyle& style) {
  double y = first_baseline.y;
  for (const std::string& paragraph : paragraphs) {
    for (const std::string& line : wrapText(canvas, paragraph, width, style.font)) {
      drawText(canvas, {first_baseline.x, y}, line, style);
      y += lineHeight(style.font);
    }
  }
  return y - first_baseline.y;
}

void drawPageMark(Canvas& canvas, const PageSize& page, const std::string& word,
                  const std::string& note, bool over) {
  constexpr Font kWordFont{.size = 120, .bold = true};
  constexpr Font kNoteFont{.size = 9.5, .bold = true};
  constexpr double kAngleRad = 0.5;  // ~29°, bottom left to top right
  // Pale, so that what is drawn with it stays readable: opaque, or red that much opaque on white.
  constexpr Rgb kPale{1.0, 0.78, 0.78};
  constexpr Rgb kRed{1.0, 0.0, 0.0};
  constexpr double kRedOpacity = 1 - 0.78;
  const Rgb colour = over ? kRed : kPale;
  const double opacity = over ? kRedOpacity : 1;
  const Canvas::Saved saved = canvas.save();
  canvas.translate(page.width_pt / 2, page.height_pt / 2);
  canvas.rotate(-kAngleRad);
  drawText(canvas, {0, kWordFont.size * kBaselineBelowMiddleEm}, word,
           {kWordFont, colour, Align::kCentre, opacity});
  drawText(canvas, {0, kWordFont.size * 0.75}, note, {kNoteFont, colour, Align::kCentre, opacity});
}

}  // namespace glarecam::render
