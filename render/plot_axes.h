// The frame of a plot: a data area on the page with a horizontal (x) and a vertical (y) axis,
// each linear or logarithmic. Maps data values to the page; gives the ticks (labelled ones, and
// on a log axis unlabelled ones at 2…9 times each decade; or an axis's own, such as months);
// draws grid lines at the labelled ticks, the ticks and their labels, the frame and both axis
// titles. A plot also records what is drawn in its data area (its ink), so that a legend can
// find the emptiest corner (plot_series.h, plot_legend.h). Page lengths are in points (pt,
// 1/72 in), the data sheet's user units; data values are in the axis's own units.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/line_style.h"
#include "render/page_geometry.h"

namespace glarecam::render {

struct Range {
  double lo = 0, hi = 0;
  bool empty() const { return !(hi > lo); }
};

enum class Scale { kLinear, kLog };

struct Tick {
  double value = 0;
  std::string label;  // empty: a minor tick
  // Where the label is centred when not under its tick: the name of the interval from this tick
  // to the next (a month on a day axis) goes between them.
  std::optional<double> label_at{};
};

struct Axis {
  Range range;  // a log axis's ends are positive
  Scale scale = Scale::kLinear;
  double step = 0;                  // linear axes: between labelled ticks, from range.lo
  std::vector<Tick> fixed_ticks{};  // when given, the axis's ticks (months, hours of the day)

  double fraction(double value) const;  // 0 at range.lo, 1 at range.hi
  bool plottable(double value) const;   // finite, and positive on a log axis
};

// 1, 2 or 5 times a power of ten, giving about six intervals over `span`.
double niceStep(double span);

// A linear axis from 0 to a whole niceStep above the largest finite value times `headroom`
// (room for a legend), or to `empty_top` when no value is above 0.
Axis linearAxisFromZero(const std::vector<double>& values, double headroom, double empty_top);

// A log axis over the whole decades around every positive finite value, at least one decade;
// `empty` when there is no such value.
Axis logAxis(const std::vector<double>& values, Range empty);

// The axis's fixed ticks when it has them. Otherwise linear: every step from range.lo, labelled
// as formatPlain; log: each decade, labelled as formatPowerOfTen, and unlabelled ticks at 2…9
// times each decade but the last.
std::vector<Tick> ticks(const Axis& axis);

// A page point covered by something drawn, weighted by how much hiding it would matter.
struct Ink {
  Point at;
  double weight = 1;
};

struct Plot {
  Box area;  // the data area on the page
  Axis x, y;
  std::vector<Ink> ink{};

  double pageX(double x_value) const;
  double pageY(double y_value) const;
  Point page(double x_value, double y_value) const { return {pageX(x_value), pageY(y_value)}; }
};

// The data area of a plot filling `frame`: room is left of it for the y tick labels and title,
// below it for the x ones.
Box plotArea(const Box& frame);

inline constexpr LineStyle kGridStyle{.colour = {0.88, 0.88, 0.90}, .width_pt = 0.5};

struct AxisTitles {
  std::string x, y;
};

// Grid, ticks with their labels, the frame, and both axis titles (the y title reading upward).
void drawAxes(Canvas& canvas, const Plot& plot, const AxisTitles& titles);

// The data area's frame alone: drawn again over what fills the area (an image hides the grid).
void drawFrame(Canvas& canvas, const Plot& plot);

}  // namespace glarecam::render
