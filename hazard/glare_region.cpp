#include "hazard/glare_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/angles.h"

namespace glarecam::hazard {
namespace {

constexpr double kPi = std::numbers::pi;
// Below this the plane of incidence is undefined (α = 0): use the up-slope direction.
constexpr double kDegenerateFrame = 1e-12;
// Golden-section search: until the bracket is below 1e-5 of the smaller half-axis; near its
// minimum f changes with the square of the distance, so q is then exact to ~1e-10.
constexpr double kGoldenTolerance = 1e-5;
constexpr double kInvPhi = 0.6180339887498949;
constexpr double kOutside = std::numeric_limits<double>::infinity();
// Below this sin²ρ, ρ/sin ρ by its series instead of atan2.
constexpr double kSeriesLimitSine2 = 0.04;

// A unit direction along the great circle from a (φ = 0) through w (φ = π/2).
Vec3 along(Vec3 a, Vec3 w, double phi) { return std::cos(phi) * a + std::sin(phi) * w; }

// The best point found on one arc: √f there and where it is, with the arc's frame and the part
// of it within reach, for refining.
struct ArcBest {
  double g = kOutside;  // √f
  double phi = 0, lo = 0, hi = 0;
  Vec3 a, w;
};

// The least √f found on the arc from a to b (unit directions, less than π apart): exact for
// circles; for ellipses the decision g ≤ 1 to the resolution (see the header), not yet refined.
ArcBest arcBest(const RegionFrame& frame, const RegionHalfAxes& axes,
                const PolygonView::Arc& edge) {
  ArcBest best;
  const Vec3 a = edge.start, w = edge.tangent;
  const double arc = edge.angle_rad;
  best.a = a, best.w = w;
  const double larger = std::max(axes.vertical_rad, axes.horizontal_rad);
  const double smaller = std::min(axes.vertical_rad, axes.horizontal_rad);
  // c·g(φ) = R cos(φ − φ0): the arc's points within `larger` of c are where
  // cos(φ − φ0) ≥ cos(larger)/R.
  const double ca = dot(frame.c, a), cw = dot(frame.c, w);
  const double r = std::sqrt(ca * ca + cw * cw);
  const double threshold = std::cos(std::min(larger, kPi)) / std::max(r, 1e-300);
  if (threshold > 1) return best;
  const double phi0 = std::atan2(cw, ca);
  const double half_width = threshold <= -1 ? kPi : std::acos(threshold);
  auto g_at = [&](double phi) {
    return std::sqrt(normalisedDistance(frame, axes, along(a, w, phi)));
  };
  for (const double centre : {phi0 - 2 * kPi, phi0, phi0 + 2 * kPi}) {
    const double lo = std::max(0.0, centre - half_width);
    const double hi = std::min(arc, centre + half_width);
    if (lo > hi) continue;
    auto keep = [&](double g, double phi) {
      if (g < best.g) best.g = g, best.phi = phi, best.lo = lo, best.hi = hi;
    };
    if (axes.vertical_rad == axes.horizontal_rad) {
      // A circle: f grows with the angle from c, least at the point nearest φ0.
      const double phi = std::clamp(centre, lo, hi);
      keep(g_at(phi), phi);
      continue;
    }
    // Ellipses. g = √f is Lipschitz along the arc: the azimuthal-equidistant plane stretches
    // an angle by at most ρ/sin ρ ≤ larger/sin(larger) here, and the normalisation by at most
    // 1/smaller. So an interval between samples g1, g2 of length Δ holds no g below
    // (g1 + g2)/2 − LΔ/2: the intervals that might reach the region (g ≤ 1) are bisected, the
    // others dropped, until a sample lands inside or every interval is dropped or shorter than
    // the resolution.
    const double lipschitz = (larger < 1e-6 ? 1.0 : larger / std::sin(larger)) / smaller;
    const double resolution = smaller / kResolutionPerHalfAxis;
    struct Interval {
      double from, to, g_from, g_to;
    };
    const int coarse = std::max(2, static_cast<int>(std::ceil((hi - lo) / (smaller / 4))));
    std::vector<Interval> open;
    double previous_phi = lo, previous_g = g_at(lo);
    keep(previous_g, lo);
    for (int i = 1; i <= coarse; ++i) {
      const double phi = lo + (hi - lo) * i / coarse;
      const double g = g_at(phi);
      keep(g, phi);
      open.push_back({previous_phi, phi, previous_g, g});
      previous_phi = phi, previous_g = g;
    }
    while (best.g > 1 && !open.empty()) {
      const Interval interval = open.back();
      open.pop_back();
      const double length = interval.to - interval.from;
      if ((interval.g_from + interval.g_to) / 2 - lipschitz * length / 2 > 1) continue;
      if (length < resolution) continue;
      const double middle = (interval.from + interval.to) / 2;
      const double g = g_at(middle);
      keep(g, middle);
      open.push_back({interval.from, middle, interval.g_from, g});
      open.push_back({middle, interval.to, g, interval.g_to});
    }
  }
  return best;
}

// q on the arc of `best` by golden-section search within a quarter of the smaller half-axis of
// its best point (the region's scale: f has one minimum there), and where on the arc it is.
struct ArcMinimum {
  double f = kOutside, phi = 0;
};
ArcMinimum refine(const RegionFrame& frame, const RegionHalfAxes& axes, const ArcBest& best) {
  const double smaller = std::min(axes.vertical_rad, axes.horizontal_rad);
  auto f = [&](double phi) { return normalisedDistance(frame, axes, along(best.a, best.w, phi)); };
  double left = std::max(best.lo, best.phi - smaller / 4);
  double right = std::min(best.hi, best.phi + smaller / 4);
  double x1 = right - kInvPhi * (right - left), x2 = left + kInvPhi * (right - left);
  double f1 = f(x1), f2 = f(x2);
  const double tolerance = kGoldenTolerance * smaller;
  while (right - left > tolerance) {
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
  ArcMinimum minimum{best.g * best.g, best.phi};
  if (f1 < minimum.f) minimum = {f1, x1};
  if (f2 < minimum.f) minimum = {f2, x2};
  return minimum;
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
  return {radians(vertical_deg / 2), radians(horizontal_deg / 2)};
}

double normalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes, Vec3 g) {
  const double x_h = dot(g, frame.e_h), x_v = dot(g, frame.e_v);
  const double sine2 = x_h * x_h + x_v * x_v;
  const double cosine = dot(g, frame.c);
  double scale = 1.0;  // ρ / sin ρ
  if (cosine > 0 && sine2 < kSeriesLimitSine2) {
    // asin(s)/s = Σ (2k)! / (4^k (k!)² (2k + 1)) s^2k to s¹²: within 3e-12 relative for
    // s < 0.2 (ρ < 11.5°).
    scale =
        1 + sine2 * (1.0 / 6 +
                     sine2 * (3.0 / 40 +
                              sine2 * (5.0 / 112 +
                                       sine2 * (35.0 / 1152 +
                                                sine2 * (63.0 / 2816 + sine2 * (231.0 / 13312))))));
  } else if (sine2 > 0) {
    const double sine = std::sqrt(sine2);
    scale = std::atan2(sine, cosine) / sine;
  }
  const double u = x_h / axes.horizontal_rad, v = x_v / axes.vertical_rad;
  return scale * scale * (u * u + v * v);
}

namespace {

PolygonView emptyView(const ArrayPolygon& array, Vec3 observer_m) {
  PolygonView view;
  view.observer_m = observer_m;
  view.in_front = seesFront(array, observer_m);
  view.centre_direction = normalised(array.centroid_m - observer_m);
  return view;
}

// A ring's directions and arcs, from its vertices in the scene's frame.
void addRing(PolygonView& view, const std::vector<Vec3>& vertices_m) {
  const std::size_t first = view.directions.size();
  for (const Vec3& vertex : vertices_m) {
    const Vec3 direction = normalised(vertex - view.observer_m);
    view.directions.push_back(direction);
    view.angular_radius_rad =
        std::max(view.angular_radius_rad, angleBetweenRad(view.centre_direction, direction));
  }
  for (std::size_t i = 0; i < vertices_m.size(); ++i) {
    const Vec3 a = view.directions[first + i];
    const Vec3 b = view.directions[first + (i + 1) % vertices_m.size()];
    view.arcs.push_back({a, normalised(b - dot(a, b) * a), angleBetweenRad(a, b)});
  }
}

// A cap wider than a hemisphere no longer holds the polygon's hull: no bound then.
void boundRadius(PolygonView& view) {
  if (view.angular_radius_rad >= kPi / 2) view.angular_radius_rad = kPi;
}

}  // namespace

PolygonView viewFrom(const ArrayPolygon& array, Vec3 observer_m) {
  PolygonView view = emptyView(array, observer_m);
  view.region = arrayRegion(array);
  addRing(view, array.vertices_m);
  boundRadius(view);
  return view;
}

PolygonView viewFrom(const ArrayPolygon& array, Vec3 observer_m, PlaneRegion region) {
  PolygonView view = emptyView(array, observer_m);
  for (const PlaneRing& ring : region.rings) {
    std::vector<Vec3> vertices_m;
    vertices_m.reserve(ring.size());
    for (const PlanePoint& point : ring) vertices_m.push_back(planeToScene(array, point));
    addRing(view, vertices_m);
  }
  view.region = std::move(region);
  boundRadius(view);
  return view;
}

double minNormalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes,
                             const ArrayPolygon& array, const PolygonView& view,
                             Vec3* glare_direction) {
  // The ray from O along c meets the plane at t > 0 (O in front, c·n = −n·s < 0).
  const double toward = dot(frame.c, array.normal);
  if (toward < 0) {
    const double t = dot(array.centroid_m - view.observer_m, array.normal) / toward;
    if (t > 0 && contains(view.region, sceneToPlane(array, view.observer_m + t * frame.c))) {
      if (glare_direction) *glare_direction = frame.c;
      return 0;
    }
  }
  // Every arc that reaches the region is refined (the least sample of one arc need not lie on
  // the arc with the least q).
  const bool circle = axes.vertical_rad == axes.horizontal_rad;
  ArcMinimum best;
  Vec3 where;
  for (const PolygonView::Arc& edge : view.arcs) {
    const ArcBest arc = arcBest(frame, axes, edge);
    const ArcMinimum minimum =
        arc.g > 1 || circle ? ArcMinimum{arc.g * arc.g, arc.phi} : refine(frame, axes, arc);
    if (minimum.f < best.f) {
      best = minimum;
      where = along(arc.a, arc.w, minimum.phi);
    }
  }
  if (glare_direction) *glare_direction = where;
  return best.f;
}

}  // namespace glarecam::hazard
