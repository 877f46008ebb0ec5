#include "pipeline/glare_picture.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "calibration/angular_plane.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/label_placement.h"
#include "render/number_format.h"
#include "render/text.h"

namespace glarecam::pipeline {
namespace {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

using calibration::AngularPlane;
using calibration::PixelPoint;
using calibration::PlanePointDeg;
using calibration::Ray;

constexpr int kCurvePoints = 360;  // per ellipse or circle: smooth at any picture size
constexpr int kAxisPoints = 48;    // an axis is a great-circle arc, curved by the lens

struct Style {
  Rgb colour;
  double alpha;     // opacity
  double width_em;  // line width in units of the label font size
  bool dashed;
};
// The limit contour in magenta, like the limit mark on the colour bar; fits in white (limit)
// and light grey (FWHM), dashed so that the traced contour shows through; circles faint.
constexpr Style kContourStyle{kLimitColour, 1, 0.14, false};
constexpr Style kLimitFitStyle{kWhite, 1, 0.12, true};
constexpr Style kFwhmFitStyle{{0.8, 0.8, 0.8}, 0.9, 0.10, true};
constexpr Style kAxisStyle{kWhite, 1, 0.08, false};
constexpr Style kCircleStyle{kWhite, 0.5, 0.07, false};
// The --thresholds ellipses: pale yellow, dotted, each labelled with its level.
constexpr Style kThresholdStyle{{1.0, 1.0, 0.6}, 0.9, 0.08, true};
// The contour ladder's fixed rungs (the method's Figure 14): thin, pale cyan, solid, each
// labelled with its level; drawn first, under everything else.
constexpr Style kLadderStyle{{0.6, 0.95, 1.0}, 0.75, 0.06, false};

constexpr Rgb kLabelOutline{0, 0, 0};
constexpr double kSmallLabelEm = 0.8;  // the circles' labels and the legend, below the axes'

Font labelFont(double font_px) { return {.size = font_px, .bold = true}; }

// One pixel of the canvas in the overlay's units (the picture may show a small frame enlarged).
double devicePixel(const Canvas& canvas) {
  const Point d = canvas.deviceToUserDistance({1, 0});
  return std::hypot(d.x, d.y);
}

// Whether `p` is within one picture size of the visible part `box`.
bool nearPicture(const Box& box, const Point& p) {
  const double w = box.x1 - box.x0, h = box.y1 - box.y0;
  return p.x > box.x0 - w && p.x < box.x1 + w && p.y > box.y0 - h && p.y < box.y1 + h;
}

// Where a ray in front of the camera lands on the picture.
Point pictureAt(const calibration::CameraModel& camera, const Ray& ray) {
  const PixelPoint p = camera.project(ray);
  return {p.x, p.y};
}

// Pixels of a curve given as rays, split where a ray is behind the camera or lands far outside
// the picture (where a distortion polynomial means nothing).
std::vector<Polyline> project(const calibration::CameraModel& camera, const std::vector<Ray>& rays,
                              const Box& box) {
  std::vector<Polyline> pieces(1);
  for (const Ray& ray : rays) {
    const Point p = ray.z > 0 ? pictureAt(camera, ray) : Point{NAN, NAN};
    if (std::isfinite(p.x) && std::isfinite(p.y) && nearPicture(box, p)) {
      pieces.back().push_back(p);
    } else if (!pieces.back().empty()) {
      pieces.emplace_back();
    }
  }
  return pieces;
}

// Rays along a curve given in an angular plane, t from t0 to t1.
template <typename Curve>
std::vector<Ray> planeCurve(const AngularPlane& plane, Curve curve, double t0, double t1,
                            int points) {
  std::vector<Ray> rays;
  for (int i = 0; i <= points; ++i) {
    const Point2 p = curve(t0 + (t1 - t0) * i / points);
    rays.push_back(plane.toRay({p.x, p.y}));
  }
  return rays;
}

void stroke(Canvas& canvas, const std::vector<Polyline>& pieces, const Style& style,
            double font_px) {
  const double width = std::max(devicePixel(canvas), style.width_em * font_px);
  canvas.setLineWidth(width);
  canvas.setLineJoin(LineJoin::kRound);
  const double dash[] = {4 * width, 3 * width};
  canvas.setDash(style.dashed ? std::span<const double>(dash) : std::span<const double>());
  canvas.setColour(style.colour, style.alpha);
  for (const Polyline& piece : pieces) {
    if (piece.size() < 2) continue;
    canvas.moveTo(piece.front());
    for (const Point& p : piece) canvas.lineTo(p);
    canvas.stroke();
  }
  canvas.setDash({});
}

// White text with a dark outline: legible on every colour of the map.
void label(Canvas& canvas, double x, double y, const std::string& text, double font_px) {
  selectFont(canvas, labelFont(font_px));
  canvas.moveTo({x, y});
  canvas.textPath(text);
  canvas.setColour(kLabelOutline);
  canvas.setLineWidth(std::max(1.5 * devicePixel(canvas), font_px / 6));
  canvas.strokePreserve();
  canvas.setColour(kWhite);
  canvas.fill();
}

// A label at `at`, inside the picture and off the drawn `lines` (label_placement.h); nothing when
// `at` is not a point (an axis end behind the camera).
void labelOffLines(Canvas& canvas, const Point& at, const Point& away, const std::string& text,
                   const Box& box, double font_px, const std::vector<Polyline>& lines) {
  if (!std::isfinite(at.x) || !std::isfinite(at.y)) return;
  const Point p =
      placeLabel({at, away, textWidth(canvas, text, labelFont(font_px)), font_px}, box, lines);
  label(canvas, p.x, p.y, text, font_px);
}

Point unitAway(const Point& from, const Point& to) {
  const double length = std::hypot(to.x - from.x, to.y - from.y);
  if (!(length > 0)) return {0, -1};
  return {(to.x - from.x) / length, (to.y - from.y) / length};
}

struct Overlay {
  calibration::CameraModel camera;
  Ray peak_ray;
  std::optional<GlareEllipse> limit, fwhm;
  bool below_limit = false;  // the maximum does not reach the limit: no glare
  std::vector<std::pair<double, GlareEllipse>> thresholds;  // level (cd/m²), ellipse
  std::vector<std::pair<double, GlareEllipse>> ladder;      // the fixed rungs, likewise
};

std::vector<Polyline> ellipseOutline(const Overlay& o, const GlareEllipse& e, const Box& box) {
  const AngularPlane plane(e.plane_centre);
  const auto curve = [&](double t) { return e.plane_ellipse.pointAt(t); };
  return project(o.camera, planeCurve(plane, curve, 0, 2 * std::numbers::pi, kCurvePoints), box);
}

// The two axes of an ellipse as arcs (added to `lines`), then each labelled at its upper or right
// end, off every line drawn (the other axis included).
void drawAxes(Canvas& canvas, const Overlay& o, const GlareEllipse& e, const std::string& prefix,
              const Box& box, double font_px, std::vector<Polyline>& lines) {
  const AngularPlane plane(e.plane_centre);
  const Ellipse& ellipse = e.plane_ellipse;
  struct AxisLabel {
    Point at, away;
    std::string text;
  };
  std::vector<AxisLabel> labels;
  for (const double t_end : {0.0, std::numbers::pi / 2}) {
    const Point2 a = ellipse.pointAt(t_end), b = ellipse.pointAt(t_end + std::numbers::pi);
    const auto chord = [&](double s) {
      return Point2{a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s};
    };
    const auto pieces = project(o.camera, planeCurve(plane, chord, 0, 1, kAxisPoints), box);
    stroke(canvas, pieces, kAxisStyle, font_px);
    lines.insert(lines.end(), pieces.begin(), pieces.end());
    const bool is_major = t_end == 0.0;
    const bool vertical = e.majorIsVertical() == is_major;
    const double length_deg = vertical ? e.vertical_deg : e.horizontal_deg;
    // Vertical axis labelled at its upper end, horizontal at its right end.
    // Only ends in front of the camera count (behind it, project() mirrors them).
    const Ray ra = plane.toRay({a.x, a.y}), rb = plane.toRay({b.x, b.y});
    if (ra.z <= 0 && rb.z <= 0) continue;
    const Point pa = pictureAt(o.camera, ra.z > 0 ? ra : rb);
    const Point pb = pictureAt(o.camera, rb.z > 0 ? rb : ra);
    const bool a_end = vertical ? pa.y < pb.y : pa.x > pb.x;
    const Point end = a_end ? pa : pb, other = a_end ? pb : pa;
    const double dx = vertical ? font_px * 0.3 : font_px * 0.4;
    const double dy = vertical ? -font_px * 0.4 : font_px * 0.35;
    labels.push_back({{end.x + dx, end.y + dy},
                      unitAway(other, end),
                      fmt::format("{}{} {:.2f}\u00b0", prefix, vertical ? "V" : "H", length_deg)});
  }
  for (const AxisLabel& l : labels)
    labelOffLines(canvas, l.at, l.away, l.text, box, font_px, lines);
}

void drawCircles(Canvas& canvas, const Overlay& o, const Box& box, double font_px) {
  const AngularPlane plane(o.peak_ray);
  for (const double radius_deg : kReferenceCirclesDeg) {
    const auto circle = [&](double t) {
      return Point2{radius_deg * std::cos(t), radius_deg * std::sin(t)};
    };
    stroke(canvas,
           project(o.camera, planeCurve(plane, circle, 0, 2 * std::numbers::pi, kCurvePoints), box),
           kCircleStyle, font_px);
    // Labelled at its lower-left point (135° in image coordinates, y down), away from the axis
    // labels (upper and right ends), right-aligned so the text stays outside the circle.
    const Point2 at = circle(3 * std::numbers::pi / 4);
    const Ray ray = plane.toRay({at.x, at.y});
    if (ray.z <= 0) continue;
    const Point p = pictureAt(o.camera, ray);
    const std::string text = fmt::format("r {:g}\u00b0", radius_deg);
    const double x =
        p.x - textWidth(canvas, text, labelFont(font_px * kSmallLabelEm)) - font_px * 0.2;
    const double y = p.y + font_px * 0.9;
    if (x > box.x0 && p.x < box.x1 && y < box.y1 && p.y > box.y0)
      label(canvas, x, y, text, font_px * kSmallLabelEm);
  }
}

// The legend only where it fits beside the spot: not on thumbnails.
constexpr double kMinLegendWidthEm = 30, kMinLegendHeightEm = 12;

void drawLegend(Canvas& canvas, const Overlay& o, const Box& box, double font_px) {
  if (box.x1 - box.x0 < kMinLegendWidthEm * font_px ||
      box.y1 - box.y0 < kMinLegendHeightEm * font_px)
    return;
  std::vector<std::string> lines;
  if (o.limit) {
    lines.push_back(o.limit->truncated
                        ? "limit contour (solid), fitted ellipse (dashed), cut by the frame"
                        : "limit contour (solid), fitted ellipse (dashed)");
  }
  if (o.fwhm) {
    lines.push_back(o.limit || !o.below_limit ? "FWHM ellipse (grey dashed)"
                                              : "no glare: FWHM ellipse (grey dashed)");
  }
  if (!o.thresholds.empty()) lines.push_back("--thresholds ellipses (yellow dotted), by level");
  if (!o.ladder.empty())
    lines.push_back("contour ladder (thin cyan): 1, 2.15, 4.64 \u00d7 10\u207f cd/m\u00b2");
  lines.push_back("circles: radius 1\u00b0, 5\u00b0, 10\u00b0, 20\u00b0 around the maximum");
  double y = box.y0 + font_px * 1.2;
  for (const std::string& line : lines) {
    label(canvas, box.x0 + font_px * 0.6, y, line, font_px * kSmallLabelEm);
    y += font_px * 1.2;
  }
}

// Each ellipse of `levels`, labelled with its level at its point at parameter `t` (π/4: upper
// right for the --thresholds, -π/4: lower right for the ladder), off `lines`.
void drawLevelLabels(Canvas& canvas, const Overlay& o,
                     const std::vector<std::pair<double, GlareEllipse>>& levels, double t,
                     const Box& box, double font_px, const std::vector<Polyline>& lines) {
  for (const auto& [level_cd_m2, e] : levels) {
    const AngularPlane plane(e.plane_centre);
    const Point2 at = e.plane_ellipse.pointAt(t);
    const Ray ray = plane.toRay({at.x, at.y});
    if (ray.z <= 0) continue;
    const Point p = pictureAt(o.camera, ray);
    const Point centre = pictureAt(o.camera, plane.toRay({0, 0}));
    labelOffLines(canvas, {p.x + font_px * 0.3, p.y - font_px * 0.3}, unitAway(centre, p),
                  formatSiPrefixed(level_cd_m2), box, font_px * kSmallLabelEm, lines);
  }
}

void drawOverlay(Canvas& canvas, const Overlay& o, double font_px) {
  const Box box = canvas.clipExtents();
  drawCircles(canvas, o, box, font_px);
  // Every line first, then the labels, each kept off all of them.
  std::vector<Polyline> lines;
  const auto draw = [&](std::vector<Polyline> pieces, const Style& style) {
    stroke(canvas, pieces, style, font_px);
    lines.insert(lines.end(), pieces.begin(), pieces.end());
  };
  for (const auto& [level, e] : o.ladder) draw(ellipseOutline(o, e, box), kLadderStyle);
  for (const auto& [level, e] : o.thresholds) draw(ellipseOutline(o, e, box), kThresholdStyle);
  if (o.fwhm) draw(ellipseOutline(o, *o.fwhm, box), kFwhmFitStyle);
  if (o.limit) {
    Polyline contour;
    for (const PixelPoint& p : o.limit->contour_px) contour.push_back({p.x, p.y});
    if (!contour.empty()) contour.push_back(contour.front());
    draw({contour}, kContourStyle);
    draw(ellipseOutline(o, *o.limit, box), kLimitFitStyle);
  }
  // Axes of the limit ellipse, or of the FWHM ellipse when the module does not glare.
  if (o.limit) {
    drawAxes(canvas, o, *o.limit, "", box, font_px, lines);
  } else if (o.fwhm) {
    drawAxes(canvas, o, *o.fwhm, "FWHM ", box, font_px, lines);
  }
  drawLevelLabels(canvas, o, o.thresholds, std::numbers::pi / 4, box, font_px, lines);
  drawLevelLabels(canvas, o, o.ladder, -std::numbers::pi / 4, box, font_px, lines);
  drawLegend(canvas, o, box, font_px);
}

}  // namespace

PictureOverlay glareOverlay(const GlareAnalysis& analysis, const calibration::CameraModel& camera,
                            const LuminancePeak& peak) {
  Overlay overlay{camera,
                  camera.ray({peak.x_px, peak.y_px}),
                  std::nullopt,
                  analysis.fwhm.ellipse,
                  analysis.limit && analysis.limit->status == EllipseStatus::kBelowLevel,
                  {},
                  {}};
  if (analysis.limit) overlay.limit = analysis.limit->ellipse;
  for (const EllipseMeasurement& m : analysis.thresholds)
    if (m.ellipse) overlay.thresholds.emplace_back(m.level_cd_m2, *m.ellipse);
  for (const ContourRung& rung : analysis.ladder) {
    if (rung.kind == ContourKind::kLadder && rung.measurement.ellipse)
      overlay.ladder.emplace_back(rung.measurement.level_cd_m2, *rung.measurement.ellipse);
  }
  return [overlay](Canvas& canvas, double font_px) { drawOverlay(canvas, overlay, font_px); };
}

}  // namespace glarecam::pipeline
