#include "hazard/glare_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glarecam::hazard {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadPerDeg = kPi / 180.0;
// Below this the plane of incidence is undefined (α = 0): use the up-slope direction.
constexpr double kDegenerateFrame = 1e-12;
// Golden-section iterations: the bracket (two sample spacings) shrinks by 0.618 each, to well
// below 1e-12 rad.
constexpr int kGoldenIterations = 60;
constexpr double kInvPhi = 0.6180339887498949;
constexpr double kOutside = std::numeric_limits<double>::infinity();

// A unit direction along the great circle from a (φ = 0) through w (φ = π/2).
Vec3 along(Vec3 a, Vec3 w, double phi) { return std::cos(phi) * a + std::sin(phi) * w; }

// The minimum of f over the arc from a to b (unit directions, less than π apart).
double arcMinimum(const RegionFrame& frame, const RegionHalfAxes& axes, Vec3 a, Vec3 b) {
  const double arc = angleBetweenRad(a, b);
  const Vec3 w = normalised(b - dot(a, b) * a);
  const double larger = std::max(axes.vertical_rad, axes.horizontal_rad);
  const double smaller = std::min(axes.vertical_rad, axes.horizontal_rad);
  // c·g(φ) = R cos(φ − φ0): the arc's points within `larger` of c are where
  // cos(φ − φ0) ≥ cos(larger)/R.
  const double ca = dot(frame.c, a), cw = dot(frame.c, w);
  const double r = std::hypot(ca, cw);
  const double phi0 = std::atan2(cw, ca);
  const double threshold = std::cos(std::min(larger, kPi)) / std::max(r, 1e-300);
  if (threshold > 1) return kOutside;
  const double half_width = threshold <= -1 ? kPi : std::acos(threshold);
  double best = kOutside;
  for (const double centre : {phi0 - 2 * kPi, phi0, phi0 + 2 * kPi}) {
    const double lo = std::max(0.0, centre - half_width);
    const double hi = std::min(arc, centre + half_width);
    if (lo > hi) continue;
    auto f = [&](double phi) { return normalisedDistance(frame, axes, along(a, w, phi)); };
    if (axes.vertical_rad == axes.horizontal_rad) {
      // A circle: f grows with the angle from c, least at the point nearest φ0.
      best = std::min(best, f(std::clamp(centre, lo, hi)));
      continue;
    }
    const double spacing = smaller / kSamplesPerHalfAxis;
    const int intervals = std::max(2, static_cast<int>(std::ceil((hi - lo) / spacing)));
    const double step = (hi - lo) / intervals;
    int best_index = 0;
    double best_sample = kOutside;
    for (int i = 0; i <= intervals; ++i) {
      const double value = f(lo + i * step);
      if (value < best_sample) {
        best_sample = value;
        best_index = i;
      }
    }
    double left = lo + std::max(best_index - 1, 0) * step;
    double right = lo + std::min(best_index + 1, intervals) * step;
    double x1 = right - kInvPhi * (right - left), x2 = left + kInvPhi * (right - left);
    double f1 = f(x1), f2 = f(x2);
    for (int i = 0; i < kGoldenIterations && right - left > 1e-13; ++i) {
      if (f1 < f2) {
        right = x2;
        x2 = x1;
        f2 = f1;
        x1 = right - kInvPhi * (right - left);
        f1 = f(x1);
      } else {
        left = x1;
        x1 = x2;
        f1 = f2;
        x2 = left + kInvPhi * (right - left);
        f2 = f(x2);
      }
    }
    best = std::min({best, best_sample, f1, f2});
  }
  return best;
}

}  // namespace

RegionFrame regionFrame(Vec3 normal, Vec3 sun, Vec3 up_slope) {
  RegionFrame frame;
  frame.c = normalised(sun - 2 * dot(normal, sun) * normal);
  Vec3 v = normal - dot(normal, frame.c) * frame.c;
  if (norm(v) < kDegenerateFrame) v = up_slope - dot(up_slope, frame.c) * frame.c;
  frame.e_v = normalised(v);
  frame.e_h = cross(frame.c, frame.e_v);
  return frame;
}

RegionHalfAxes halfAxesRad(double vertical_deg, double horizontal_deg) {
  return {vertical_deg / 2 * kRadPerDeg, horizontal_deg / 2 * kRadPerDeg};
}

double normalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes, Vec3 g) {
  const double x_h = dot(g, frame.e_h), x_v = dot(g, frame.e_v);
  const double sine = std::hypot(x_h, x_v);
  const double rho = std::atan2(sine, dot(g, frame.c));
  // ρ / sin ρ → 1 at the centre.
  const double scale = sine > 1e-300 ? rho / sine : 1.0;
  const double u = x_h / axes.horizontal_rad, v = x_v / axes.vertical_rad;
  return scale * scale * (u * u + v * v);
}

PolygonView viewFrom(const ArrayPolygon& array, Vec3 observer_m) {
  PolygonView view;
  view.observer_m = observer_m;
  view.in_front = dot(observer_m - array.centroid_m, array.normal) > 0;
  view.centre_direction = normalised(array.centroid_m - observer_m);
  for (const Vec3& vertex : array.vertices_m) {
    const Vec3 direction = normalised(vertex - observer_m);
    view.directions.push_back(direction);
    view.angular_radius_rad =
        std::max(view.angular_radius_rad, angleBetweenRad(view.centre_direction, direction));
  }
  // A cap wider than a hemisphere no longer holds the polygon's hull: no bound then.
  if (view.angular_radius_rad >= kPi / 2) view.angular_radius_rad = kPi;
  return view;
}

double minNormalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes,
                             const ArrayPolygon& array, const PolygonView& view) {
  // The ray from O along c meets the plane at t > 0 (O in front, c·n = −n·s < 0).
  const double toward = dot(frame.c, array.normal);
  if (toward < 0) {
    const double t = dot(array.centroid_m - view.observer_m, array.normal) / toward;
    if (t > 0 && containsPlanePoint(array, view.observer_m + t * frame.c)) return 0;
  }
  double best = kOutside;
  const std::size_t count = view.directions.size();
  for (std::size_t i = 0; i < count; ++i)
    best = std::min(best,
                    arcMinimum(frame, axes, view.directions[i], view.directions[(i + 1) % count]));
  return best;
}

}  // namespace glarecam::hazard
