#include "render/plot_axes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/canvas.h"
#include "render/number_format.h"
#include "render/text.h"

namespace glarecam::render {
namespace {

constexpr double kYAxisGutterPt = 44;  // left of a data area: tick labels, rotated title
constexpr double kXAxisGutterPt = 28;  // below a data area: tick labels, title
constexpr double kRightPaddingPt = 6;  // right of a data area
constexpr double kTickLengthPt = 3.5;
constexpr double kMinorTickLengthPt = 2;
constexpr double kTickLabelGapPt = 2;  // between a tick and its label
constexpr Font kTickFont{.size = 7.5};
constexpr Font kAxisTitleFont{.size = 8};
constexpr LineStyle kFrameStyle{.colour = kFrameColour, .width_pt = 0.7};

void drawYTicks(Canvas& canvas, const Plot& plot) {
  const Box& a = plot.area;
  for (const Tick& tick : ticks(plot.y)) {
    const double y = plot.pageY(tick.value);
    const bool major = !tick.label.empty();
    drawSegment(canvas, {a.x0 - (major ? kTickLengthPt : kMinorTickLengthPt), y}, {a.x0, y},
                kFrameStyle);
    if (!major) continue;
    drawSegment(canvas, {a.x0, y}, {a.x1, y}, kGridStyle);
    const double label_y = plot.pageY(tick.label_at.value_or(tick.value));
    drawText(
        canvas,
        {a.x0 - kTickLengthPt - kTickLabelGapPt, label_y + kBaselineBelowMiddleEm * kTickFont.size},
        tick.label, {kTickFont, kInk, Align::kRight});
  }
}

void drawXTicks(Canvas& canvas, const Plot& plot) {
  const Box& a = plot.area;
  for (const Tick& tick : ticks(plot.x)) {
    const double x = plot.pageX(tick.value);
    const bool major = !tick.label.empty();
    if (major) drawSegment(canvas, {x, a.y0}, {x, a.y1}, kGridStyle);
    drawSegment(canvas, {x, a.y1}, {x, a.y1 + (major ? kTickLengthPt : kMinorTickLengthPt)},
                kFrameStyle);
    if (!major) continue;
    drawText(canvas,
             {plot.pageX(tick.label_at.value_or(tick.value)),
              a.y1 + kTickLengthPt + kTickLabelGapPt + kTickFont.size},
             tick.label, {kTickFont, kInk, Align::kCentre});
  }
}

}  // namespace

double Axis::fraction(double value) const {
  return scale == Scale::kLog ? (std::log10(value) - std::log10(range.lo)) /
                                    (std::log10(range.hi) - std::log10(range.lo))
                              : (value - range.lo) / (range.hi - range.lo);
}

bool Axis::plottable(double value) const {
  return std::isfinite(value) && (scale == Scale::kLinear || value > 0);
}

double niceStep(double span) {
  constexpr double kTargetIntervals = 6;
  const double raw = span / kTargetIntervals;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double multiple : {1.0, 2.0, 5.0}) {
    if (multiple * decade >= raw) return multiple * decade;
  }
  return 10 * decade;
}

Axis linearAxisFromZero(const std::vector<double>& values, double headroom, double empty_top) {
  double top = 0;
  for (const double v : values)
    if (std::isfinite(v)) top = std::max(top, v);
  top = top > 0 ? top * headroom : empty_top;
  const double step = niceStep(top);
  return {.range = {0, std::ceil(top / step) * step}, .step = step};
}

Axis logAxis(const std::vector<double>& values, Range empty) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const double v : values) {
    if (!std::isfinite(v) || v <= 0) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(hi > 0)) return {.range = empty, .scale = Scale::kLog};
  const double lo_decade = std::floor(std::log10(lo));
  const double hi_decade = std::max(std::ceil(std::log10(hi)), lo_decade + 1);
  return {.range = {std::pow(10.0, lo_decade), std::pow(10.0, hi_decade)}, .scale = Scale::kLog};
}

std::vector<Tick> ticks(const Axis& axis) {
  constexpr int kMinorsPerDecade = 9;
  constexpr double kStepTolerance = 1e-6;  // of a step: the top tick despite rounding
  if (!axis.fixed_ticks.empty()) return axis.fixed_ticks;
  std::vector<Tick> ticks;
  if (axis.scale == Scale::kLinear) {
    const int steps =
        static_cast<int>((axis.range.hi - axis.range.lo) / axis.step + kStepTolerance);
    for (int i = 0; i <= steps; ++i) {
      const double v = axis.range.lo + i * axis.step;
      ticks.push_back({v, formatPlain(v)});
    }
    return ticks;
  }
  const int lo = static_cast<int>(std::lround(std::log10(axis.range.lo)));
  const int hi = static_cast<int>(std::lround(std::log10(axis.range.hi)));
  for (int decade = lo; decade <= hi; ++decade) {
    const double base = std::pow(10.0, decade);
    ticks.push_back({base, formatPowerOfTen(decade)});
    if (decade == hi) break;
    for (int m = 2; m <= kMinorsPerDecade; ++m) ticks.push_back({m * base, ""});
  }
  return ticks;
}

double Plot::pageX(double x_value) const { return area.x0 + x.fraction(x_value) * area.width(); }

double Plot::pageY(double y_value) const { return area.y1 - y.fraction(y_value) * area.height(); }

Box plotArea(const Box& frame) {
  return {frame.x0 + kYAxisGutterPt, frame.y0, frame.x1 - kRightPaddingPt,
          frame.y1 - kXAxisGutterPt};
}

void drawFrame(Canvas& canvas, const Plot& plot) {
  const Box& a = plot.area;
  applyLineStyle(canvas, kFrameStyle);
  canvas.rectangle(a);
  canvas.stroke();
}

void drawAxes(Canvas& canvas, const Plot& plot, const AxisTitles& titles) {
  drawYTicks(canvas, plot);
  drawXTicks(canvas, plot);
  drawFrame(canvas, plot);
  const Box& a = plot.area;
  const TextStyle title_style{kAxisTitleFont, kInk, Align::kCentre};
  drawText(canvas, {(a.x0 + a.x1) / 2, a.y1 + kXAxisGutterPt - kTickLabelGapPt}, titles.x,
           title_style);
  drawVerticalText(canvas, {a.x0 - kYAxisGutterPt + kAxisTitleFont.size, (a.y0 + a.y1) / 2},
                   titles.y, title_style);
}

}  // namespace glarecam::render
