#include "pipeline/render/plot_series.h"

#include <cairo.h>

namespace glarecam::pipeline {
namespace {

constexpr double kCurveInkWeight = 1;    // a sample
constexpr double kMarkerInkWeight = 12;  // hiding a measured point is worse than a curve

}  // namespace

std::vector<double> sample(const PlotFunction& f, Range x) {
  std::vector<double> values;
  if (x.empty()) return values;
  for (int i = 0; i <= kCurveSamples; ++i)
    values.push_back(f(x.lo + (x.hi - x.lo) * i / kCurveSamples));
  return values;
}

void drawCurve(cairo_t* cr, Plot& plot, const PlotFunction& f, Range x, const LineStyle& style) {
  const std::vector<double> values = sample(f, x);
  std::vector<DataPoint> points;
  for (std::size_t i = 0; i < values.size(); ++i)
    points.push_back({x.lo + (x.hi - x.lo) * i / kCurveSamples, values[i]});
  drawLine(cr, plot, points, style);
}

void drawLine(cairo_t* cr, Plot& plot, const std::vector<DataPoint>& points,
              const LineStyle& style) {
  cairo_save(cr);
  cairo_rectangle(cr, plot.area.x0, plot.area.y0, plot.area.width(), plot.area.height());
  cairo_clip(cr);
  applyLineStyle(cr, style);
  bool drawing = false;
  for (const DataPoint& point : points) {
    if (!plot.x.plottable(point.x) || !plot.y.plottable(point.y)) {
      drawing = false;
      continue;
    }
    const Point p = plot.page(point.x, point.y);
    drawing ? cairo_line_to(cr, p.x, p.y) : cairo_move_to(cr, p.x, p.y);
    drawing = true;
    plot.ink.push_back({p, kCurveInkWeight});
  }
  cairo_stroke(cr);
  cairo_restore(cr);
}

void drawMarkers(cairo_t* cr, Plot& plot, const std::vector<DataPoint>& points,
                 const MarkerStyle& style) {
  for (const DataPoint& point : points) {
    if (!plot.y.plottable(point.y)) continue;
    const Point p = plot.page(point.x, point.y);
    drawMarker(cr, p, style);
    plot.ink.push_back({p, kMarkerInkWeight});
  }
}

}  // namespace glarecam::pipeline
