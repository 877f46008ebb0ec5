// What a plot shows in its data area (plot_axes.h): functions sampled into curves, series of
// values (one a day, say) as lines through their points, and measured points as markers. Each
// is clipped to the data area or skipped where it cannot be plotted, and leaves its ink in the
// plot's record for the legend (plot_legend.h): a line lightly, a marker heavily, since hiding a
// measured point is worse than hiding a stretch of line.
#pragma once

#include <functional>
#include <vector>

#include "render/line_style.h"
#include "render/markers.h"
#include "render/plot_axes.h"

namespace glarecam::render {

// An x value to a y value, both in the axes' units; NaN where the function is undefined.
using PlotFunction = std::function<double(double)>;

// Intervals a curve is sampled at over its x range: smooth at the data sheet's plot sizes.
inline constexpr int kCurveSamples = 240;

// f at kCurveSamples + 1 evenly spaced x from x.lo to x.hi; nothing when the range is empty.
std::vector<double> sample(const PlotFunction& f, Range x);

// f over the x range as a line, broken where it is not plottable (NaN, or ≤ 0 on a log y axis).
void drawCurve(Canvas& canvas, Plot& plot, const PlotFunction& f, Range x, const LineStyle& style);

struct DataPoint {
  double x = 0, y = 0;
};

// The points in their order joined by straight lines, broken at a point that is not plottable;
// every point is kept (a series is not resampled, so a one-day peak stays).
void drawLine(Canvas& canvas, Plot& plot, const std::vector<DataPoint>& points,
              const LineStyle& style);

// A marker at each plottable point.
void drawMarkers(Canvas& canvas, Plot& plot, const std::vector<DataPoint>& points,
                 const MarkerStyle& style);

}  // namespace glarecam::render
