// The glare region of one array at one instant and the exact test of whether an observer sees
// it (../shared/docs/hazard.md, steps 3–7).
//
// Frame: c = s − 2(n·s)n is the direction from the observer toward the sun's mirror image; e_v
// is the component of n perpendicular to c, normalised (in the plane of incidence: the profile's
// vertical axis), e_h = c × e_v. At α = 0 that plane is undefined and the array's up-slope
// direction stands in for n.
//
// Region: a direction g maps into the azimuthal-equidistant plane around c as
// ρ·(g·e_h, g·e_v)/|(g·e_h, g·e_v)| with ρ = angle(g, c), and the normalised distance
//   f(g) = (x_h / (H/2))² + (x_v / (V/2))²
// is ≤ 1 inside the region. f has one minimum (0, at c) and grows along every great circle
// leaving c, so its minimum over a polygon seen from O is 0 when the ray from O along c meets
// the polygon, and otherwise lies on the polygon's boundary: on one of the great-circle arcs its
// edges make as seen from O.
//
// The test (minNormalisedDistance) decides q ≤ 1 exactly up to a stated resolution, and finds q
// where it is ≤ 1:
//   - circular regions (H = V): analytically (the angular distance from c to each arc);
//   - ellipses: only the part of each arc within the larger half-axis of c can reach f ≤ 1
//     (found analytically). It is sampled every quarter of the smaller half-axis; √f is
//     Lipschitz along the arc (constant L = (ρ/sin ρ)max / smaller half-axis: the projection's
//     stretch over the normalisation), so an interval between two samples g1, g2 of length Δ has
//     no point below (g1 + g2)/2 − LΔ/2. Intervals that might reach the region are bisected, the
//     others dropped, until a sample lands inside, or every interval is dropped or shorter than
//     the resolution, 1/kResolutionPerHalfAxis of the smaller half-axis.
// Error bound: a sample lies within half the resolution of every point of an interval it drops,
// so a polygon is always found to glare when it holds a point with √f ≤ 1 − L·resolution/2,
// i.e. when it meets the region shrunk about c by (π/2)/2048 < 0.08 % (for a 4°-wide region,
// 0.0015°: a third of a second of the sun's motion); one that only grazes the outer 0.08 % may be
// missed. Where it is found, q is refined by golden-section search (to 1e-5 of the smaller
// half-axis: q to ~1e-10) within a quarter of that half-axis of the best sample, on every arc
// that reaches the region. glare_region_test checks the decision and q against brute force
// sampling of the polygon on random geometries.
#pragma once

#include <vector>

#include "hazard/plane_region.h"
#include "hazard/scene.h"
#include "hazard/vec3.h"

namespace glarecam::hazard {

inline constexpr int kResolutionPerHalfAxis = 1024;

struct RegionFrame {
  Vec3 c;    // unit, observer → the sun's mirror image in the array
  Vec3 e_h;  // unit, the horizontal axis H
  Vec3 e_v;  // unit, the vertical axis V, in the plane of incidence
};

// Steps 3–4 for a unit normal, a unit sun direction with n·s > 0, and the array's up-slope.
RegionFrame regionFrame(Vec3 normal, Vec3 sun, Vec3 up_slope);

struct RegionHalfAxes {
  double vertical_rad = 0, horizontal_rad = 0;  // half of V and H
};
RegionHalfAxes halfAxesRad(double vertical_deg, double horizontal_deg);

// f(g) for a unit direction g.
double normalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes, Vec3 direction);

// The array, or a region of its plane (what obstructions, shadows and a field of view leave of
// it: plane_region.h), seen from an observer. The whole array's view is constant over the year
// and computed once per pair.
struct PolygonView {
  Vec3 observer_m;
  bool in_front = false;  // (O − P₀)·n > 1 cm (the planarity tolerance): else edge-on or behind
  PlaneRegion region;     // what is seen, in the array's plane frame (even–odd rings)
  std::vector<Vec3> directions;  // unit, observer → each vertex of every ring
  // Each edge of every ring as seen: the great-circle arc from one vertex's direction toward the
  // next one's, as its start, the unit tangent there and its angle.
  struct Arc {
    Vec3 start, tangent;
    double angle_rad = 0;
  };
  std::vector<Arc> arcs;
  Vec3 centre_direction;          // unit, observer → the array's centroid
  double angular_radius_rad = 0;  // every vertex lies within this of centre_direction
};
PolygonView viewFrom(const ArrayPolygon& array, Vec3 observer_m);
// A region of the array's plane (within the array) seen from the observer; an empty region has
// no arcs and never glares.
PolygonView viewFrom(const ArrayPolygon& array, Vec3 observer_m, PlaneRegion region);

// min over the polygon of f; exact (see above) when it is ≤ 1, otherwise only some value > 1.
// `glare_direction`, when given, receives the unit direction from the observer to where the
// minimum lies (c itself when the ray along c meets the polygon): where the glare is seen.
double minNormalisedDistance(const RegionFrame& frame, const RegionHalfAxes& axes,
                             const ArrayPolygon& array, const PolygonView& view,
                             Vec3* glare_direction = nullptr);

}  // namespace glarecam::hazard
