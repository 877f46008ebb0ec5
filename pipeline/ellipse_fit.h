// Least-squares ellipse through 2-D points. The direct algebraic fit of Fitzgibbon, Pilu and
// Fisher (1999, "Direct least square fitting of ellipses"), in the numerically stable form of
// Halíř and Flusser (1998), gives the start; a geometric fit (Levenberg–Marquardt on the
// orthogonal point-to-ellipse distances) then refines it, because algebraic distances weigh
// the points unevenly around an elongated ellipse. The geometric fit also yields how each
// fitted semi-axis moves when one point moves, which is what propagating contour noise into
// axis uncertainty needs. Units are the points' units (pixels or degrees); angles in radians.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace glarecam::pipeline {

struct Point2 {
  double x = 0, y = 0;
};

struct Ellipse {
  Point2 centre;
  double semi_major = 0, semi_minor = 0;
  double angle_rad = 0;            // of the major axis from +x toward +y, in (-pi/2, pi/2]
  Point2 pointAt(double t) const;  // centre + R(angle) (a cos t, b sin t)
};

struct EllipseFit {
  Ellipse ellipse;
  std::vector<double> residuals;  // signed orthogonal distances, positive outside
  std::vector<Point2> normals;    // outward unit normal at each point's nearest ellipse point
  double rms_residual = 0;
  // For each point, d(semi_major, semi_minor) / d(point x, point y) as a row-major 2x2 matrix.
  std::vector<std::array<double, 4>> axis_sensitivity;
  // For each point, d(angle_rad) / d(point x, point y).
  std::vector<std::array<double, 2>> angle_sensitivity;
};

// The conic fit alone. It is ellipse-specific: points on a hyperbola or a parabola still get
// their closest ellipse (judge the shape by the residuals). Nothing when the points determine
// no conic (fewer than 5, all on one line) or only an imaginary one.
std::optional<Ellipse> fitEllipseDirect(std::span<const Point2> points);

// The geometric fit, started from `initial` (e.g. the fit of nearly the same points) or else
// from the direct fit.
std::optional<EllipseFit> fitEllipse(std::span<const Point2> points,
                                     const std::optional<Ellipse>& initial = std::nullopt);

}  // namespace glarecam::pipeline
