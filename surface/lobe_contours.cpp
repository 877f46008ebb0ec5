#include "surface/lobe_contours.h"

#include <cmath>

#include "core/angles.h"

namespace glarecam::surface {

using calibration::PlanePointDeg;

double luminanceAt(const BrdfModel& model, double alpha_deg, const PlanePointDeg& p,
                   const LobeOptions& options) {
  const SpecularFrame frame(alpha_deg, 0);
  const Ray outgoing = frame.sampleRayAt(p);
  // The sun's centre and the two axes across it: e1 across the plane of incidence, e2 in it.
  const Ray sun = sampleDirection(alpha_deg, 0);
  const double a = radians(alpha_deg);
  const Ray e1{0, 1, 0}, e2{std::cos(a), 0, -std::sin(a)};
  const int rings = std::max(1, options.disc_rings);
  const double radius = options.sun_half_angle_deg;
  double sum = 0, weights = 0;
  for (int k = 1; k <= (radius > 0 ? rings : 1); ++k) {
    // Ring k spans radii R(k-1)/K to Rk/K: its area is (2k-1)/K² of the disc's, spread over
    // 6(2k-1) points (1 for the centre), at the radius that halves it.
    const int n = k == 1 ? 1 : 6 * (2 * k - 1);
    const double inner = radius * (k - 1) / rings, outer = radius * k / rings;
    const double r = k == 1 ? 0.0 : std::sqrt((inner * inner + outer * outer) / 2);
    const double weight = (k == 1 ? 1.0 : (2.0 * k - 1)) / n;
    for (int j = 0; j < n; ++j) {
      const double angle = 2 * std::numbers::pi * (j + 0.5 * (k % 2)) / n;
      const double u = std::tan(radians(r * std::cos(angle))),
                   v = std::tan(radians(r * std::sin(angle)));
      Ray i{sun.x + u * e1.x + v * e2.x, sun.y + u * e1.y + v * e2.y, sun.z + u * e1.z + v * e2.z};
      const double n_i = std::sqrt(i.x * i.x + i.y * i.y + i.z * i.z);
      i = {i.x / n_i, i.y / n_i, i.z / n_i};
      sum += weight * model.brdfSr(i, outgoing) * i.z;
      weights += weight;
    }
  }
  return options.illuminance_lx * sum / weights;
}

namespace {

// Along the line from `from` in `direction` (unit, degrees): the distance where L falls below
// `level` (bisected to 1e-10°), none within `search`.
std::optional<double> crossing(const BrdfModel& model, double alpha, const PlanePointDeg& from,
                               double dx, double dy, double level, const LobeOptions& options) {
  // Bisected far below any use (1e-10°): a fit differentiates the axes numerically.
  constexpr double kStepDeg = 0.05, kToleranceDeg = 1e-10;
  double inside = 0;
  for (double t = kStepDeg; t <= options.search_deg; t += kStepDeg) {
    const PlanePointDeg p{from.x_deg + t * dx, from.y_deg + t * dy};
    if (luminanceAt(model, alpha, p, options) < level) {
      double outside = t;
      while (outside - inside > kToleranceDeg) {
        const double mid = (inside + outside) / 2;
        const PlanePointDeg q{from.x_deg + mid * dx, from.y_deg + mid * dy};
        (luminanceAt(model, alpha, q, options) >= level ? inside : outside) = mid;
      }
      return (inside + outside) / 2;
    }
    inside = t;
  }
  return std::nullopt;
}

}  // namespace

LobeContours lobePeak(const BrdfModel& model, double alpha_deg, const LobeOptions& options) {
  LobeContours out;
  out.alpha_deg = alpha_deg;
  // The peak on the plane of incidence: a scan, then golden-section refinement.
  constexpr double kScanDeg = 10, kScanStepDeg = 0.05;
  double best_y = 0, best = -1;
  for (double y = -kScanDeg; y <= kScanDeg; y += kScanStepDeg) {
    const double l = luminanceAt(model, alpha_deg, {0, y}, options);
    if (l > best) {
      best = l;
      best_y = y;
    }
  }
  double lo = best_y - kScanStepDeg, hi = best_y + kScanStepDeg;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 60; ++k) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    if (luminanceAt(model, alpha_deg, {0, a}, options) >=
        luminanceAt(model, alpha_deg, {0, b}, options))
      hi = b;
    else
      lo = a;
  }
  out.peak = {0, (lo + hi) / 2};
  out.peak_cd_m2 = luminanceAt(model, alpha_deg, out.peak, options);
  return out;
}

ContourAxes contourAxes(const BrdfModel& model, const LobeContours& peak, double level,
                        const LobeOptions& options) {
  ContourAxes axes;
  axes.level_cd_m2 = level;
  if (!(level < peak.peak_cd_m2)) return axes;
  const double alpha_deg = peak.alpha_deg;
  const auto up = crossing(model, alpha_deg, peak.peak, 0, 1, level, options);
  const auto down = crossing(model, alpha_deg, peak.peak, 0, -1, level, options);
  if (up && down) {
    axes.vertical_deg = *up + *down;
    const PlanePointDeg centre{0, peak.peak.y_deg + (*up - *down) / 2};
    const auto right = crossing(model, alpha_deg, centre, 1, 0, level, options);
    const auto left = crossing(model, alpha_deg, centre, -1, 0, level, options);
    if (right && left) axes.horizontal_deg = *right + *left;
  }
  return axes;
}

LobeContours lobeContours(const BrdfModel& model, double alpha_deg,
                          std::span<const double> levels_cd_m2, const LobeOptions& options) {
  LobeContours out = lobePeak(model, alpha_deg, options);
  for (double level : levels_cd_m2) out.contours.push_back(contourAxes(model, out, level, options));
  return out;
}

}  // namespace glarecam::surface
