#include "render/plot_series.h"

#include "render/canvas.h"

namespace glarecam::render {
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

void drawCurve(Canvas& canvas, Plot& plot, const PlotFunction& f, Range x, const LineStyle& style) {
  const std::vector<double> values = sample(f, x);
  std::vector<DataPoint> points;
  for (std::size_t i = 0; i < values.size(); ++i)
    points.push_back({x.lo + (x.hi - x.lo) * i / kCurveSamples, values[i]});
  drawLine(canvas, plot, points, style);
}

void drawLine(Canvas& canvas, Plot& plot, const std::vector<DataPoint>& points,
              const LineStyle& style) {
  const Canvas::Saved saved = canvas.save();
  canvas.rectangle(plot.area);
  canvas.clip();
  applyLineStyle(canvas, style);
  bool drawing = false;
  for (const DataPoint& point : points) {
    if (!plot.x.plottable(point.x) || !plot.y.plottable(point.y)) {
      drawing = false;
      continue;
    }
    const Point p = plot.page(point.x, point.y);
    drawing ? canvas.lineTo(p) : canvas.moveTo(p);
    drawing = true;
    plot.ink.push_back({p, kCurveInkWeight});
  }
  canvas.stroke();
}

void drawMarkers(Canvas& canvas, Plot& plot, const std::vector<DataPoint>& points,
                 const MarkerStyle& style) {
  for (const DataPoint& point : points) {
    if (!plot.y.plottable(point.y)) continue;
    const Point p = plot.page(point.x, point.y);
    drawMarker(canvas, p, style);
    plot.ink.push_back({p, kMarkerInkWeight});
  }
}

}  // namespace glarecam::render
