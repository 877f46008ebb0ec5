#include "hazard/scene_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "hazard/hazard_report.h"
#include "hazard/obstruction.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/line_style.h"
#include "render/markers.h"
#include "render/number_format.h"
#include "render/plot_axes.h"
#include "render/plot_legend.h"
#include "render/text.h"

namespace glarecam::hazard {
// Named after the file: in a unity build this file shares a translation unit with the library's
// other pictures, whose helpers have names of their own.
namespace scene_plan {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

constexpr Font kPlanLabelFont{.size = 6.5};
constexpr Font kPlanNorthFont{.size = 9, .bold = true};

// ---- The plan's colours: Okabe–Ito, as the charts ----

constexpr Rgb kArrayColour{0x00 / 255.0, 0x72 / 255.0, 0xB2 / 255.0};  // blue
constexpr Rgb kRouteColour{0x00 / 255.0, 0x9E / 255.0, 0x73 / 255.0};  // bluish green
constexpr Rgb kAreaColour{0xCC / 255.0, 0x79 / 255.0, 0xA7 / 255.0};   // reddish purple
constexpr Rgb kWorstColour{0xD5 / 255.0, 0x5E / 255.0, 0x00 / 255.0};  // vermillion
constexpr Rgb kObstructionFill{0.78, 0.78, 0.80};
constexpr Rgb kObstructionEdge{0.45, 0.45, 0.48};
constexpr double kArrayFillLightening = 0.7;
constexpr double kViewWedgeOpacity = 0.12;
constexpr double kViewWedgePt = 20;    // the radius of an observer's field of view
constexpr double kFacingArrowPt = 16;  // an array's facing, from its centre
constexpr double kArrowHeadPt = 4.5;
constexpr double kHaloPt = 2.4;  // white outline around a plan's label
constexpr double kObserverMarkerPt = 4.6;
constexpr double kPointDotPt = 3.2;  // a route's or an area's receptor point
constexpr double kPointKeyPt = 4;    // the same in the legend, where it stands alone
constexpr double kWorstMarkerPt = 8;
constexpr double kScaleBarShare = 0.2;    // of the plan's width, at most
constexpr double kPlanPadShare = 0.08;    // around what the plan shows
constexpr double kMinPlanSpanM = 20;      // a scene smaller than this is shown this wide
constexpr double kCornerInkWeight = 1e6;  // the north arrow and the scale bar: no legend there
constexpr double kItemInkWeight = 10;
constexpr LineStyle kArrayEdge{.colour = kArrayColour, .width_pt = 0.8};
constexpr LineStyle kRouteLine{.colour = kRouteColour, .width_pt = 1.3};
constexpr LineStyle kAreaOutline{.colour = kAreaColour, .width_pt = 0.7, .dash = Dash::kDashed};
constexpr LineStyle kArrowLine{.colour = kInk, .width_pt = 0.8};

// A label with a white outline, readable over what the plan draws under it.
void drawHaloText(Canvas& canvas, Point baseline, const std::string& text, const Font& font,
                  const Rgb& colour, Align align) {
  const double width = textWidth(canvas, text, font);
  const double shift = align == Align::kLeft ? 0 : align == Align::kCentre ? width / 2 : width;
  const Canvas::Saved saved = canvas.save();
  selectFont(canvas, font);
  canvas.moveTo({baseline.x - shift, baseline.y});
  canvas.textPath(text);
  canvas.setColour(kWhite);
  canvas.setLineWidth(kHaloPt);
  canvas.setLineJoin(LineJoin::kRound);
  canvas.strokePreserve();
  canvas.setColour(colour);
  canvas.fill();
}

// ---- Geometry on the page ----

// Arrows point along a compass azimuth; y runs down the page.
Point along(Point from, double azimuth_deg, double length_pt) {
  const double a = azimuth_deg * std::numbers::pi / 180;
  return {from.x + length_pt * std::sin(a), from.y - length_pt * std::cos(a)};
}

void drawArrow(Canvas& canvas, Point from, double azimuth_deg, double length_pt,
               const LineStyle& style) {
  const Point tip = along(from, azimuth_deg, length_pt);
  drawSegment(canvas, from, along(from, azimuth_deg, length_pt - kArrowHeadPt), style);
  constexpr double kHeadHalfAngleDeg = 25;
  const Point left = along(tip, azimuth_deg + 180 - kHeadHalfAngleDeg, kArrowHeadPt);
  const Point right = along(tip, azimuth_deg + 180 + kHeadHalfAngleDeg, kArrowHeadPt);
  canvas.moveTo(tip);
  canvas.lineTo(left);
  canvas.lineTo(right);
  canvas.lineTo(tip);
  canvas.setColour(style.colour);
  canvas.fill();
}

// A receptor point of a route or an area: a plain dot (a marker's white ring would read as a gap
// in the route's line).
void drawDot(Canvas& canvas, Point at, const Rgb& colour) {
  canvas.newSubPath();
  canvas.arc(at, kPointDotPt / 2, 0, 2 * std::numbers::pi);
  canvas.setColour(colour);
  canvas.fill();
}

void polygonPath(Canvas& canvas, const std::vector<Point>& points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    i == 0 ? canvas.moveTo(points[i]) : canvas.lineTo(points[i]);
  if (!points.empty()) canvas.lineTo(points.front());
}

// An obstruction's footprint: an extruded one's lowest face, a planar one's outline seen from
// above (a vertical wall: a line).
std::vector<Vec3> footprintOf(const Obstruction& obstruction) {
  if (obstruction.faces.empty()) return {};
  const auto lowest = std::min_element(
      obstruction.faces.begin(), obstruction.faces.end(),
      [](const ArrayPolygon& a, const ArrayPolygon& b) { return a.centroid_m.z < b.centroid_m.z; });
  return obstruction.faces.size() > 1 ? lowest->vertices_m : obstruction.faces.front().vertices_m;
}

double topOf(const Obstruction& obstruction) {
  double top = -std::numeric_limits<double>::infinity();
  for (const ArrayPolygon& face : obstruction.faces)
    for (const Vec3& v : face.vertices_m) top = std::max(top, v.z);
  return top;
}

// The convex hull of points (Andrew's monotone chain), for an area's outline.
std::vector<Point> convexHull(std::vector<Point> points) {
  std::sort(points.begin(), points.end(),
            [](const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3) return points;
  const auto turn = [](const Point& o, const Point& a, const Point& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<Point> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// 1, 2 or 5 times a power of ten, at most `most`.
double roundLength(double most) {
  const double decade = std::pow(10.0, std::floor(std::log10(most)));
  for (const double multiple : {5.0, 2.0, 1.0})
    if (multiple * decade <= most) return multiple * decade;
  return decade;
}

// The plot of the plan: east across, north up, one scale for both (metres per point the same),
// around everything the scene holds.
Plot planPlot(const Scene& scene, const Box& frame) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  const auto include = [&](const Vec3& v) {
    x0 = std::min(x0, v.x);
    x1 = std::max(x1, v.x);
    y0 = std::min(y0, v.y);
    y1 = std::max(y1, v.y);
  };
  for (const ArrayPolygon& array : scene.arrays)
    for (const Vec3& v : array.vertices_m) include(v);
  for (const Observer& observer : scene.observers) include(observer.position_m);
  for (const Obstruction& obstruction : scene.obstructions)
    for (const Vec3& v : footprintOf(obstruction)) include(v);
  if (!(x1 >= x0)) x0 = y0 = -kMinPlanSpanM / 2, x1 = y1 = kMinPlanSpanM / 2;
  const double pad = kPlanPadShare * std::max({x1 - x0, y1 - y0, kMinPlanSpanM});
  const Box area = plotArea(frame);
  const double metres_per_pt = std::max(std::max(x1 - x0, kMinPlanSpanM) + 2 * pad,
                                        std::max(y1 - y0, kMinPlanSpanM) + 2 * pad) /
                               std::min(area.width(), area.height());
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const double half_w = area.width() * metres_per_pt / 2,
               half_h = area.height() * metres_per_pt / 2;
  const auto metreTicks = [](double lo, double hi) {
    const double step = niceStep(hi - lo);
    std::vector<Tick> ticks;
    for (double v = std::ceil(lo / step) * step; v <= hi; v += step)
      ticks.push_back(
          {std::abs(v) < step * 1e-9 ? 0.0 : v, formatPlain(std::abs(v) < step * 1e-9 ? 0.0 : v)});
    return ticks;
  };
  return {.area = area,
          .x = {.range = {cx - half_w, cx + half_w},
                .fixed_ticks = metreTicks(cx - half_w, cx + half_w)},
          .y = {.range = {cy - half_h, cy + half_h},
                .fixed_ticks = metreTicks(cy - half_h, cy + half_h)}};
}

void drawNorthArrow(Canvas& canvas, Plot& plot) {
  constexpr double kInsetPt = 16, kLengthPt = 26;
  const Point base{plot.area.x1 - kInsetPt,
                   plot.area.y0 + kInsetPt + kPlanNorthFont.size + kLengthPt};
  drawArrow(canvas, base, 0, kLengthPt, {.colour = kInk, .width_pt = 1.4});
  drawHaloText(canvas, {base.x, base.y - kLengthPt - 3}, "N", kPlanNorthFont, kInk, Align::kCentre);
  for (const double down : {0.0, 0.5, 1.0})
    plot.ink.push_back({{base.x, base.y - down * kLengthPt}, kCornerInkWeight});
}

void drawScaleBar(Canvas& canvas, Plot& plot) {
  constexpr double kInsetPt = 12, kTickPt = 4;
  const double metres_per_pt = (plot.x.range.hi - plot.x.range.lo) / plot.area.width();
  const double length_m = roundLength(kScaleBarShare * plot.area.width() * metres_per_pt);
  const double length_pt = length_m / metres_per_pt;
  const Point left{plot.area.x0 + kInsetPt, plot.area.y1 - kInsetPt};
  const Point right{left.x + length_pt, left.y};
  const LineStyle bar{.colour = kInk, .width_pt = 1.4};
  drawSegment(canvas, left, right, bar);
  drawSegment(canvas, {left.x, left.y - kTickPt}, {left.x, left.y}, bar);
  drawSegment(canvas, {right.x, right.y - kTickPt}, {right.x, right.y}, bar);
  drawHaloText(canvas, {(left.x + right.x) / 2, left.y - kTickPt - 2},
               fmt::format("{} m", formatPlain(length_m)), kPlanLabelFont, kInk, Align::kCentre);
  for (const double share : {0.0, 0.5, 1.0})
    plot.ink.push_back({{left.x + share * length_pt, left.y}, kCornerInkWeight});
}

void drawPlan(Canvas& canvas, const Box& frame, const Scene& scene,
              const std::vector<std::size_t>& worst_points) {
  Plot plot = planPlot(scene, frame);
  drawAxes(canvas, plot, {.x = "east (m)", .y = "north (m)"});
  const auto page = [&plot](const Vec3& v) { return plot.page(v.x, v.y); };
  std::vector<LegendEntry> legend;
  const Canvas::Saved clipped = canvas.save();
  canvas.rectangle(plot.area);
  canvas.clip();

  // Obstructions under everything.
  for (const Obstruction& obstruction : scene.obstructions) {
    std::vector<Point> outline;
    for (const Vec3& v : footprintOf(obstruction)) outline.push_back(page(v));
    polygonPath(canvas, outline);
    canvas.setColour(kObstructionFill);
    canvas.fillPreserve();
    applyLineStyle(canvas, {.colour = kObstructionEdge, .width_pt = 1.2});
    canvas.stroke();
  }
  // The arrays, each with an arrow the way its front faces.
  for (const ArrayPolygon& array : scene.arrays) {
    std::vector<Point> outline;
    for (const Vec3& v : array.vertices_m) outline.push_back(page(v));
    polygonPath(canvas, outline);
    canvas.setColour(lightened(kArrayColour, kArrayFillLightening));
    canvas.fillPreserve();
    applyLineStyle(canvas, kArrayEdge);
    canvas.stroke();
    const Point centre = page(array.centroid_m);
    if (const std::optional<double> facing = facingAzimuthDeg(array))
      drawArrow(canvas, centre, *facing, kFacingArrowPt, {.colour = kArrayColour, .width_pt = 1.1});
    plot.ink.push_back({centre, kItemInkWeight});
  }

  const std::vector<Receptor> receptors = sceneReceptors(scene);
  bool any_route = false, any_area = false, any_worst = false;
  for (const Receptor& receptor : receptors) {
    std::vector<Point> points;
    for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
      points.push_back(page(scene.observers[o].position_m));
      plot.ink.push_back({points.back(), kItemInkWeight});
    }
    if (points.empty()) continue;
    if (receptor.kind == ReceptorKind::kObserver) {
      for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
        const Observer& observer = scene.observers[o];
        const Point at = page(observer.position_m);
        for (const double azimuth : observer.view_azimuths_deg) {
          const double half = std::min(observer.field_of_view_deg, 180.0);
          const double from = (azimuth - half - 90) * std::numbers::pi / 180;
          const double to = (azimuth + half - 90) * std::numbers::pi / 180;
          canvas.moveTo(at);
          canvas.arc(at, kViewWedgePt, from, to);
          canvas.lineTo(at);
          canvas.setColour(kInk, kViewWedgeOpacity);
          canvas.fill();
          drawArrow(canvas, at, azimuth, kViewWedgePt, kArrowLine);
        }
        drawMarker(canvas, at, {.colour = kInk, .size_pt = kObserverMarkerPt});
      }
    } else if (receptor.kind == ReceptorKind::kRoute) {
      any_route = true;
      applyLineStyle(canvas, kRouteLine);
      for (std::size_t i = 0; i < points.size(); ++i)
        i == 0 ? canvas.moveTo(points[i]) : canvas.lineTo(points[i]);
      canvas.stroke();
      for (const Point& p : points) drawDot(canvas, p, kRouteColour);
      const Observer& middle = scene.observers[receptor.first + receptor.count / 2];
      for (const double azimuth : middle.view_azimuths_deg)
        drawArrow(canvas, page(middle.position_m), azimuth, kViewWedgePt,
                  {.colour = kRouteColour, .width_pt = 1.1});
    } else {
      any_area = true;
      const std::vector<Point> hull = convexHull(points);
      if (hull.size() >= 3) {
        polygonPath(canvas, hull);
        applyLineStyle(canvas, kAreaOutline);
        canvas.stroke();
      }
      for (const Point& p : points) drawDot(canvas, p, kAreaColour);
    }
  }
  // The worst points over the routes and areas; then every label over everything.
  for (const std::size_t o : worst_points) {
    if (o >= scene.observers.size()) continue;
    any_worst = true;
    drawMarker(canvas, page(scene.observers[o].position_m),
               {.colour = kWorstColour, .size_pt = kWorstMarkerPt, .hollow = true});
  }
  for (const Obstruction& obstruction : scene.obstructions) {
    const double top = topOf(obstruction);
    const Point centre = page(obstruction.centre_m);
    drawHaloText(canvas, {centre.x, centre.y + kBaselineBelowMiddleEm * kPlanLabelFont.size},
                 obstruction.faces.size() > 1
                     ? fmt::format("{} ({} m)", obstruction.name, formatSignificant(top, 3))
                     : obstruction.name,
                 kPlanLabelFont, kObstructionEdge, Align::kCentre);
  }
  for (const ArrayPolygon& array : scene.arrays) {
    const Point centre = page(array.centroid_m);
    drawHaloText(canvas, {centre.x, centre.y + kPlanLabelFont.size + 4}, array.name, kPlanLabelFont,
                 kArrayColour, Align::kCentre);
  }
  constexpr double kLabelOffsetPt = 5;
  for (const Receptor& receptor : receptors) {
    if (receptor.count == 0) continue;
    if (receptor.kind == ReceptorKind::kObserver) {
      for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
        const Point at = page(scene.observers[o].position_m);
        drawHaloText(canvas, {at.x + kLabelOffsetPt, at.y - kLabelOffsetPt},
                     scene.observers[o].name, kPlanLabelFont, kInk, Align::kLeft);
      }
      continue;
    }
    const Rgb colour = receptor.kind == ReceptorKind::kRoute ? kRouteColour : kAreaColour;
    Point at = page(scene.observers[receptor.first].position_m);
    if (receptor.kind == ReceptorKind::kArea) {
      double sx = 0, sy = 0;
      for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
        sx += page(scene.observers[o].position_m).x;
        sy += page(scene.observers[o].position_m).y;
      }
      at = {sx / receptor.count, sy / receptor.count};
    }
    drawHaloText(canvas, {at.x + kLabelOffsetPt, at.y - kLabelOffsetPt}, receptor.name,
                 kPlanLabelFont, colour, Align::kLeft);
  }

  drawNorthArrow(canvas, plot);
  drawScaleBar(canvas, plot);
  legend.push_back({"array (arrow: the way its front faces)", std::nullopt,
                    MarkerStyle{.colour = lightened(kArrayColour, kArrayFillLightening / 2),
                                .shape = MarkerShape::kSquare,
                                .size_pt = 7}});
  if (!scene.obstructions.empty())
    legend.push_back(
        {"obstruction (footprint, top height)", std::nullopt,
         MarkerStyle{.colour = kObstructionFill, .shape = MarkerShape::kSquare, .size_pt = 7}});
  legend.push_back({"observer (wedge: the directions it counts)", std::nullopt,
                    MarkerStyle{.colour = kInk, .size_pt = kObserverMarkerPt}});
  if (any_route)
    legend.push_back({"route, its points (arrow: direction of travel)", kRouteLine,
                      MarkerStyle{.colour = kRouteColour, .size_pt = kPointKeyPt}});
  if (any_area)
    legend.push_back({"area's receptor points", std::nullopt,
                      MarkerStyle{.colour = kAreaColour, .size_pt = kPointKeyPt}});
  if (any_worst)
    legend.push_back(
        {"worst point of a route or area", std::nullopt,
         MarkerStyle{.colour = kWorstColour, .size_pt = kWorstMarkerPt, .hollow = true}});
  drawLegend(canvas, plot, legend);
}

}  // namespace scene_plan

Status drawScenePlan(render::Canvas& canvas, const render::Box& frame, const Scene& scene,
                     const std::vector<std::size_t>& worst_points) {
  scene_plan::drawPlan(canvas, frame, scene, worst_points);
  return canvas.status();
}

}  // namespace glarecam::hazard
