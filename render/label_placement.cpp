#include "render/label_placement.h"

#include <algorithm>

namespace glarecam::render {
namespace {

constexpr double kStepEm = 0.25;
constexpr int kSteps = 32;  // 8 em

Point insideBox(const Point& at, double width_px, const Box& box, double font_px) {
  // min(max(...)): defined even on pictures too small for the label (unlike std::clamp).
  return {std::min(std::max(at.x, box.x0 + font_px * 0.2), box.x1 - width_px - font_px * 0.2),
          std::min(std::max(at.y, box.y0 + font_px * 1.1), box.y1 - font_px * 0.3)};
}

}  // namespace

bool labelCovers(const Point& baseline, double width_px, double font_px,
                 const std::vector<Polyline>& lines) {
  const double margin = font_px * 0.25;
  const double x0 = baseline.x - margin, x1 = baseline.x + width_px + margin;
  const double y0 = baseline.y - font_px * 0.8 - margin, y1 = baseline.y + font_px * 0.2 + margin;
  for (const Polyline& line : lines)
    for (const Point& p : line)
      if (p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) return true;
  return false;
}

Point placeLabel(const LabelSpec& label, const Box& box, const std::vector<Polyline>& lines) {
  for (int step = 0; step <= kSteps; ++step) {
    const double d = label.font_px * kStepEm * step;
    const Point candidate =
        insideBox({label.at.x + label.away.x * d, label.at.y + label.away.y * d}, label.width_px,
                  box, label.font_px);
    if (!labelCovers(candidate, label.width_px, label.font_px, lines)) return candidate;
  }
  return insideBox(label.at, label.width_px, box, label.font_px);
}

}  // namespace glarecam::render
